#pragma once
/// A separable Gaussian blur of a float image on the CPU (edges repeat the border pixel). On a
/// CPU rasteriser this is several times faster than two float render passes.

#include <vector>

namespace rescuesim {

/// Blurs `image` (row-major, width x height) in place with standard deviation `sigma` pixels
/// (kernel radius ceil(3 sigma)); sigma <= 0 leaves it unchanged.
void gaussian_blur(std::vector<float>& image, int width, int height, double sigma);

}  // namespace rescuesim
