#pragma once
/// Rendering speed beside a bare OpenGL baseline on the same kind of context, for
/// `rescuesim bench` and bench/render_bench.cpp (each figure beside its baseline, same run).
/// Library rs_render_bench, linked only by those two: rs_render carries no benchmark code.

#include "render/renderer.h"

namespace rescuesim {

/// Frames per second of a bare GL loop on a headless context chosen as Renderer::create_headless
/// chooses it: `triangles` triangles tiling the whole view (every pixel covered about once),
/// a trivial shader, an RGBA8 + 32-bit float depth target, and an RGB8 glReadPixels each frame.
/// Runs for about `seconds` (after a few warm-up frames). Throws Error like create_headless.
double bare_gl_frames_per_second(int width, int height, int triangles, double seconds);

/// Which image a renderer benchmark renders.
enum class BenchImage {
  color,    ///< Renderer::color
  depth,    ///< Renderer::depth
  thermal,  ///< Renderer::thermal with a 1.5 px blur
};

/// Frames per second of `renderer` rendering `view` as `image`, read back to memory, for about
/// `seconds` after a few warm-up frames.
double renderer_frames_per_second(Renderer& renderer, const CameraView& view, BenchImage image, double seconds);

}  // namespace rescuesim
