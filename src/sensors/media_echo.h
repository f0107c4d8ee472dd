#pragma once
/// Ray sensors through smoke and dust (docs/environment.md): two-way Beer-Lambert loss of the
/// target's echo, and early echoes from the medium itself, drawn from the sensor's own stream.

#include <span>
#include <vector>

#include "core/rng.h"
#include "core/sim_time.h"
#include "raycast/ray_scene.h"
#include "world/media.h"
#include "world/world.h"

namespace rescuesim {

/// The world's media at `stamp` in `band`, into `out` (cleared first). Empty when the world has
/// none or none that the band feels; then a sensor does no per-ray work at all.
void sensor_media(const World& world, SimTime stamp, SensingBand band, std::vector<MediumVolume>& out);

/// What one ray's echo becomes through the media. The ray's segment runs from its origin to the
/// surface it hit at `distance`, or to max_distance when it hit nothing (`distance` +inf); its
/// one-way optical depth tau is exact (world/media.h). With tau = 0 (the segment misses every
/// medium) nothing is drawn and `distance` comes back as it was; so it does for NaN. Otherwise
/// one uniform number u is drawn:
///  - u < exp(-2 tau): the target's echo survives both ways: `distance`;
///  - else, with probability `echo_probability` (the excess of u, rescaled), the medium returns an
///    early echo from where the pulse was first scattered: optical depth Exp(1) conditioned to
///    fall inside the segment (inverse transform: -ln(1 - v (1 - exp(-tau))), v the rest of u
///    rescaled), mapped to a distance along the ray;
///  - else no return: +inf.
float echo_through_media(float distance, const Ray& ray, std::span<const MediumVolume> media, double echo_probability, Rng& rng,
                         std::vector<MediumSegment>& scratch);

}  // namespace rescuesim
