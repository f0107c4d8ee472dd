// The CPU Gaussian blur of thermal images: weights that sum to one, the kernel's shape on a
// single hot pixel, and the same floats as the plain pixel-at-a-time filter it replaced.

#include "render/image_blur.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace rescuesim {
namespace {

/// The filter one pixel at a time, clamped at every tap (the implementation before stop 29).
void reference_blur(std::vector<float>& image, int width, int height, double sigma) {
  const int radius = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<float> w(static_cast<std::size_t>(radius) + 1);
  double sum = 0;
  for (int i = 0; i <= radius; ++i) sum += (i == 0 ? 1 : 2) * std::exp(-0.5 * i * i / (sigma * sigma));
  for (int i = 0; i <= radius; ++i) w[static_cast<std::size_t>(i)] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)) / sum);
  std::vector<float> tmp(image.size());
  const auto at = [&](const std::vector<float>& im, int x, int y) {
    return im[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float acc = w[0] * at(image, x, y);
      for (int i = 1; i <= radius; ++i) {
        acc += w[static_cast<std::size_t>(i)] * (at(image, std::max(0, x - i), y) + at(image, std::min(width - 1, x + i), y));
      }
      tmp[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = acc;
    }
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float acc = w[0] * at(tmp, x, y);
      for (int i = 1; i <= radius; ++i) {
        acc += w[static_cast<std::size_t>(i)] * (at(tmp, x, std::max(0, y - i)) + at(tmp, x, std::min(height - 1, y + i)));
      }
      image[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = acc;
    }
  }
}

TEST(GaussianBlur, SameFloatsAsThePixelAtATimeFilter) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<float> kelvin(250.0f, 320.0f);
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{640, 480}, {33, 17}, {7, 5}, {3, 20}, {1, 1}, {12, 1}}) {
    for (double sigma : {0.4, 1.5, 4.0}) {
      std::vector<float> image(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
      for (float& v : image) v = kelvin(gen);
      std::vector<float> expected = image;
      reference_blur(expected, w, h, sigma);
      gaussian_blur(image, w, h, sigma);
      EXPECT_EQ(std::memcmp(image.data(), expected.data(), image.size() * sizeof(float)), 0) << w << " x " << h << ", sigma " << sigma;
    }
  }
}

TEST(GaussianBlur, KeepsAUniformImageAndSpreadsAHotPixelAsAGaussian) {
  std::vector<float> flat(50 * 40, 300.0f);
  gaussian_blur(flat, 50, 40, 1.5);
  for (float v : flat) EXPECT_NEAR(v, 300.0f, 1e-3f);
  // one pixel of 1 in 0: the result is the kernel, w(dx) w(dy) with w(d) ~ exp(-d^2 / (2 s^2))
  std::vector<float> dot(41 * 41, 0.0f);
  dot[20 * 41 + 20] = 1.0f;
  gaussian_blur(dot, 41, 41, 1.5);
  const double centre = dot[20 * 41 + 20];
  EXPECT_NEAR(centre, 1.0 / (2 * M_PI * 1.5 * 1.5), 0.01);  // the continuous Gaussian's peak, 0.0707
  EXPECT_NEAR(dot[20 * 41 + 21] / centre, std::exp(-0.5 / 2.25), 1e-5);
  EXPECT_NEAR(dot[22 * 41 + 20] / centre, std::exp(-2.0 / 2.25), 1e-5);
  double total = 0;
  for (float v : dot) total += v;
  EXPECT_NEAR(total, 1.0, 1e-5);
}

TEST(GaussianBlur, ZeroSigmaLeavesTheImage) {
  std::vector<float> image = {1, 2, 3, 4};
  gaussian_blur(image, 2, 2, 0);
  EXPECT_EQ(image, (std::vector<float>{1, 2, 3, 4}));
}

}  // namespace
}  // namespace rescuesim
