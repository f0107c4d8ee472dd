#pragma once
/// Smoke and dust as the sensors feel them (docs/environment.md): each medium's extinction
/// coefficient per sensing band, its footprint at a sim time (growth and drift), and the exact
/// optical depth of a ray through the media (a polygon prism each, clipped analytically). Pure
/// functions, for the ray sensors and later the cameras.

#include <span>
#include <vector>

#include "core/pose.h"
#include "world/world_spec.h"

namespace rescuesim {

/// The bands rescuesim's sensors sense in.
enum class SensingBand {
  visible,             ///< ~550 nm: colour cameras, the eye
  near_infrared,       ///< 905 nm: pulsed time-of-flight lidar
  long_wave_infrared,  ///< 8-14 um: thermal cameras
  ultrasound,          ///< 40 kHz: sonar
};

/// The extinction coefficient of a medium of `kind` in `band` as a fraction of its visible one
/// (the reasoning is in media.cpp and docs/environment.md): near infrared 1 (smoke and dust),
/// long-wave infrared 0.05 (smoke) and 0.7 (dust), ultrasound 0 (smoke) and 0.01 (dust).
double band_ratio(MediumSpec::Kind kind, SensingBand band);

/// The medium's extinction coefficient in `band` (1/m): density * band_ratio.
double extinction(const MediumSpec& medium, SensingBand band);

/// Koschmieder's visibility (m) through a medium of visible extinction `sigma` (1/m): 3 / sigma,
/// the distance at which a black target's contrast falls to 5 % (+inf for sigma 0).
double visibility(double sigma);

/// Of the rays a medium stops in `band` before they reach their target, the fraction that
/// come back to the sensor as an early echo from the medium itself: 0.5 for near infrared and
/// visible, 0 for long-wave infrared and ultrasound (docs/environment.md).
double medium_echo_probability(SensingBand band);

/// The single-scattering albedo of a medium in visible light: the fraction of the light it
/// removes from a ray that it scatters rather than absorbs, and so the brightness of the haze it
/// lays over a camera image (the airlight): 0.3 for smoke (soot from flaming combustion is mostly
/// black carbon), 0.9 for mineral dust (docs/environment.md).
double scattering_albedo(MediumSpec::Kind kind);

/// The footprint at sim time t (s): each edge moved outward by growth * t (corners mitred), then
/// the whole moved by drift * t. Exact for convex footprints; a concave one's grown outline may
/// cross itself, and is then read with the even-odd rule.
Polygon2 medium_outline(const MediumSpec& medium, double t);

/// A medium at one instant in one band, ready for rays: a prism of `outline` between `bottom`
/// and `top` with extinction `sigma`, and its bounding box.
struct MediumVolume {
  Polygon2 outline;       ///< counter-clockwise, m
  double bottom = 0;      ///< m
  double top = 0;         ///< m
  double sigma = 0;       ///< 1/m in the band
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();  ///< bounding box, world frame (m)
};

/// The media at sim time t (s) in `band`, into `out` (cleared first); media whose coefficient in
/// the band is 0 are left out, so an empty `out` means the band sees clear air.
void media_at(std::span<const MediumSpec> media, double t, SensingBand band, std::vector<MediumVolume>& out);

/// Whether the segment from `origin` along unit `direction` for `length` metres meets the
/// volume's bounding box.
bool segment_meets_box(const MediumVolume& v, const Vec3& origin, const Vec3& direction, double length);

/// A stretch of a ray inside one medium: distances along the ray (m) and the medium's sigma.
struct MediumSegment {
  double enter = 0, leave = 0;  ///< m along the ray, enter < leave
  double sigma = 0;             ///< 1/m
};

/// The stretches of the segment [0, length] of the ray (origin, unit direction) inside the
/// volume's prism, appended to `out`, computed exactly (the ray clipped against the bottom and
/// top planes and against the footprint's edges).
void ray_in_volume(const MediumVolume& v, const Vec3& origin, const Vec3& direction, double length,
                   std::vector<MediumSegment>& out);

/// The one-way optical depth of the segment [0, length] through every volume (dimensionless:
/// the sum of sigma times the length inside); the stretches inside go to `segments` (cleared
/// first). Volumes whose box the segment misses cost a box test only.
double optical_depth(std::span<const MediumVolume> volumes, const Vec3& origin, const Vec3& direction, double length,
                     std::vector<MediumSegment>& segments);

/// The distance along the ray (m) at which its optical depth through `segments` reaches `tau`;
/// +inf when the segments hold less than `tau`. Overlapping segments add their sigmas.
double distance_at_depth(std::span<const MediumSegment> segments, double tau);

}  // namespace rescuesim
