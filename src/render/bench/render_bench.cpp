#include "render/bench/render_bench.h"

#include <chrono>

namespace rescuesim {

double renderer_frames_per_second(Renderer& renderer, const CameraView& view, BenchImage image, double seconds) {
  ColorImage color;
  DepthImage depth;
  ThermalImage thermal;
  const auto frame = [&] {
    switch (image) {
      case BenchImage::color: renderer.color(view, color); break;
      case BenchImage::depth: renderer.depth(view, depth); break;
      case BenchImage::thermal: renderer.thermal(view, 1.5, thermal); break;
    }
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
