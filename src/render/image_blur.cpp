#include "render/image_blur.h"

#include <algorithm>
#include <cmath>

namespace rescuesim {

void gaussian_blur(std::vector<float>& image, int width, int height, double sigma) {
  if (sigma <= 0 || width <= 0 || height <= 0) return;
  const int radius = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<float> w(static_cast<std::size_t>(radius) + 1);
  double sum = 0;
  for (int i = 0; i <= radius; ++i) sum += (i == 0 ? 1 : 2) * std::exp(-0.5 * i * i / (sigma * sigma));
  for (int i = 0; i <= radius; ++i) w[static_cast<std::size_t>(i)] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)) / sum);
  const auto W = static_cast<std::size_t>(width);
  std::vector<float> tmp(image.size());
  // Each output pixel is w0 p + w1 (left1 + right1) + w2 (left2 + right2) + ..., summed in that
  // order; the loops run over whole rows per term (so they vectorise) and keep the order, so the
  // result is the same float for float as one pixel at a time.
  // across each row: clamped at the borders, straight in between
  const int lo = std::min(radius, width), hi = std::max(lo, width - radius);
  for (int y = 0; y < height; ++y) {
    const float* row = &image[static_cast<std::size_t>(y) * W];
    float* out = &tmp[static_cast<std::size_t>(y) * W];
    const auto clamped = [&](int x) {
      float acc = w[0] * row[x];
      for (int i = 1; i <= radius; ++i) acc += w[static_cast<std::size_t>(i)] * (row[std::max(0, x - i)] + row[std::min(width - 1, x + i)]);
      return acc;
    };
    for (int x = 0; x < lo; ++x) out[x] = clamped(x);
    for (int x = lo; x < hi; ++x) out[x] = w[0] * row[x];
    for (int i = 1; i <= radius; ++i) {
      const float wi = w[static_cast<std::size_t>(i)];
      for (int x = lo; x < hi; ++x) out[x] += wi * (row[x - i] + row[x + i]);
    }
    for (int x = hi; x < width; ++x) out[x] = clamped(x);
  }
  // then down each column, a whole row of pixels per term
  for (int y = 0; y < height; ++y) {
    float* out = &image[static_cast<std::size_t>(y) * W];
    const float* centre = &tmp[static_cast<std::size_t>(y) * W];
    for (std::size_t x = 0; x < W; ++x) out[x] = w[0] * centre[x];
    for (int i = 1; i <= radius; ++i) {
      const float wi = w[static_cast<std::size_t>(i)];
      const float* up = &tmp[static_cast<std::size_t>(std::max(0, y - i)) * W];
      const float* down = &tmp[static_cast<std::size_t>(std::min(height - 1, y + i)) * W];
      for (std::size_t x = 0; x < W; ++x) out[x] += wi * (up[x] + down[x]);
    }
  }
}

}  // namespace rescuesim
