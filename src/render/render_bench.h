#pragma once
/// Rendering speed beside a bare OpenGL baseline on the same kind of context, for
/// `rescuesim bench` and bench/render_bench.cpp (each figure beside its baseline, same run).

#include "render/renderer.h"

namespace rescuesim {

/// Frames per second of a bare GL loop on a headless context chosen as Renderer::create_headless
/// chooses it: `triangles` triangles tiling the whole view (every pixel covered about once),
/// a trivial shader, an RGBA8 + 32-bit float depth target, and an RGB8 glReadPixels each frame.
/// Runs for about `seconds` (after a few warm-up frames). Throws Error like create_headless.
double bare_gl_frames_per_second(int width, int height, int triangles, double seconds);

/// Frames per second of `renderer` rendering `view` (kind 0: colour, 1: depth, 2: thermal with a
/// 1.5 px blur), images read back to memory, for about `seconds` after a few warm-up frames.
double renderer_frames_per_second(Renderer& renderer, const CameraView& view, int kind, double seconds);

}  // namespace rescuesim
