#pragma once
/// Smoke and dust as the camera shaders take them: convex prisms, each with its extinction
/// coefficient in the three bands the cameras sense (visible light for the colour camera, near
/// infrared for the depth camera's own light, long-wave infrared for the thermal camera) and its
/// scattering albedo. The media's physics (coefficients per band, growth and drift) is
/// world/media.h's; this only cuts footprints into the convex pieces a shader clips a ray
/// against. No graphics types.

#include <span>
#include <vector>

#include "core/pose.h"
#include "world/world_spec.h"

namespace rescuesim {

/// One convex prism of a medium.
struct FogPiece {
  std::vector<Vec3> half_planes;  ///< (nx, ny, d), n a unit vector: the footprint is where nx x + ny y <= d (m)
  std::vector<Vec2> corners;      ///< the footprint's vertices (m): with bottom and top, the prism's corners
  double bottom = 0, top = 0;     ///< m above the floor
  double sigma_visible = 0;       ///< extinction coefficients (1/m)
  double sigma_near_infrared = 0;
  double sigma_long_wave = 0;
  double albedo = 0;              ///< single-scattering albedo in visible light
};

/// The pieces of `media` at sim time t (s), footprints from medium_outline: a convex footprint
/// is one piece, a concave one a piece per triangle of its triangulation (a grown concave
/// footprint that crosses itself is replaced by its convex hull, a slight overestimate). Media
/// with zero density are left out.
std::vector<FogPiece> fog_pieces(std::span<const MediumSpec> media, double t);

/// The optical depths (visible, near infrared, long-wave infrared) of the segment a→b through
/// `pieces`: the reference the shaders compute per pixel.
Vec3 fog_optical_depth(std::span<const FogPiece> pieces, const Vec3& a, const Vec3& b);

}  // namespace rescuesim
