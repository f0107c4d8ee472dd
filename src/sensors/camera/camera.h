#pragma once
/// Camera sensors: turning rendered images into ROS-shaped messages — colour (rgb8, with
/// optional Brown distortion, exposure and pixel noise), depth (32FC1 metres or 16UC1
/// millimetres, NaN outside the range, noise growing with distance, a PointCloud2 in the
/// optical frame) and thermal (mono16 at 0.01 K per count, and mono8 over a temperature
/// window, with NETD-like noise), each with its CameraInfo; and the decoders that turn those
/// messages back into images.

#include "msgs/messages.h"
#include "render/renderer.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// Where a robot's camera sensor looks from, for the renderer (the robot is not hidden: a head
/// camera may see its own chassis, as a real one would).
CameraView camera_view(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec);

/// The pinhole intrinsics of a camera spec.
Intrinsics camera_intrinsics(const CameraSpec& c);

/// CameraInfo with K and P from the intrinsics and D from the distortion (plumb_bob).
msg::CameraInfo camera_info(const SensorSpec& spec, const msg::Header& header);

/// Colour image message; `rng` draws the pixel noise.
msg::Image color_message(const ColorImage& image, const SensorSpec& spec, const msg::Header& header, Rng& rng);

/// Depth image message (NaN/0 outside [min_range, max_range]) and its point cloud.
msg::Image depth_message(const DepthImage& image, const SensorSpec& spec, const msg::Header& header, Rng& rng);
msg::PointCloud2 depth_cloud(const msg::Image& depth, const SensorSpec& spec);

/// Thermal images: mono16 (0.01 K per count) with NETD noise, and the mono8 window.
msg::Image thermal_mono16(const ThermalImage& image, const SensorSpec& spec, const msg::Header& header, Rng& rng);
msg::Image thermal_mono8(const msg::Image& mono16, const SensorSpec& spec);

/// The victims that show as warm blobs in a thermal image: a victim counts when, around the
/// pixel where one of its body parts projects (within the camera's range), a 3x3 window holds a
/// pixel at least `contrast` kelvin above ambient. Occluded victims do not show: the image holds
/// whatever is in front of them.
std::vector<int> victims_in_thermal_image(const World& world, const CameraView& view, const SensorSpec& spec,
                                          const msg::Image& mono16, double contrast);

/// The inverses of the messages above, for figures and tools (rows top-down, `step` honoured,
/// either byte order): rgb8 or bgr8 to a ColorImage; 32FC1 (m) or 16UC1 (mm) to a DepthImage with
/// +inf where there is no data (NaN, 0); mono16 (0.01 K per count) to a ThermalImage. Each throws
/// Error naming the function and the encoding for any other encoding, or when the data is shorter
/// than height × step.
ColorImage color_image_of(const msg::Image& m);
DepthImage depth_image_of(const msg::Image& m);
ThermalImage thermal_image_of(const msg::Image& m);

/// Kelvin of a mono16 count.
inline double kelvin_of_count(std::uint16_t c) { return c * 0.01; }

}  // namespace rescuesim
