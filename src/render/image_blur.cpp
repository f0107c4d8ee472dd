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
  std::vector<float> tmp(image.size());
  // across each row, then down each column
  for (int y = 0; y < height; ++y) {
    const float* row = &image[static_cast<std::size_t>(y) * static_cast<std::size_t>(width)];
    float* out = &tmp[static_cast<std::size_t>(y) * static_cast<std::size_t>(width)];
    for (int x = 0; x < width; ++x) {
      float acc = w[0] * row[x];
      for (int i = 1; i <= radius; ++i) acc += w[static_cast<std::size_t>(i)] * (row[std::max(0, x - i)] + row[std::min(width - 1, x + i)]);
      out[x] = acc;
    }
  }
  for (int y = 0; y < height; ++y) {
    float* out = &image[static_cast<std::size_t>(y) * static_cast<std::size_t>(width)];
    for (int x = 0; x < width; ++x) {
      float acc = w[0] * tmp[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
      for (int i = 1; i <= radius; ++i) {
        const std::size_t up = static_cast<std::size_t>(std::max(0, y - i)) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        const std::size_t down = static_cast<std::size_t>(std::min(height - 1, y + i)) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        acc += w[static_cast<std::size_t>(i)] * (tmp[up] + tmp[down]);
      }
      out[x] = acc;
    }
  }
}

}  // namespace rescuesim
