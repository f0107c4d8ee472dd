#include "render/render_bench.h"

#include <chrono>

#include <fmt/format.h>

#include "core/error.h"

namespace rescuesim {

double renderer_frames_per_second(Renderer& renderer, const CameraView& view, int kind, double seconds) {
  if (kind < 0 || kind > 2) {
    throw Error(SourceRef{"", 0, "renderer_frames_per_second"}, fmt::format("unknown image kind {} (0 colour, 1 depth, 2 thermal)", kind));
  }
  ColorImage color;
  DepthImage depth;
  ThermalImage thermal;
  const auto frame = [&] {
    if (kind == 0) renderer.color(view, color);
    else if (kind == 1) renderer.depth(view, depth);
    else renderer.thermal(view, 1.5, thermal);
  };
  // warm up: shader variants, targets of this size
  for (int i = 0; i < 3; ++i) frame();
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  int frames = 0;
  double elapsed = 0;
  do {
    frame();
    ++frames;
    elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  } while (elapsed < seconds);
  return frames / elapsed;
}

}  // namespace rescuesim
