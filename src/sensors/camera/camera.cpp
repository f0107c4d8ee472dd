#include "sensors/camera/camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"
#include "sensors/noise.h"

namespace rescuesim {

namespace {

BrownDistortion distortion_of(const CameraSpec& c) {
  // ROS plumb_bob order: k1, k2, p1, p2, k3
  BrownDistortion d;
  d.k1 = c.distortion[0];
  d.k2 = c.distortion[1];
  d.p1 = c.distortion[2];
  d.p2 = c.distortion[3];
  d.k3 = c.distortion[4];
  return d;
}

/// Automatic exposure: the gain that brings the mean linear luminance of `rgb` (sRGB bytes) to
/// 0.18, within [exposure / max_gain, exposure * max_gain].
double auto_exposure_gain(const std::vector<std::uint8_t>& rgb, const CameraSpec& c) {
  static const auto table = [] {
    std::array<double, 256> t{};
    for (int i = 0; i < 256; ++i) t[static_cast<std::size_t>(i)] = srgb_to_linear(i / 255.0);
    return t;
  }();
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
    sum += 0.2126 * table[rgb[i]] + 0.7152 * table[rgb[i + 1]] + 0.0722 * table[rgb[i + 2]];
    ++n;
  }
  const double mean = n > 0 ? sum / static_cast<double>(n) : 0.18;
  return c.exposure * std::clamp(0.18 / std::max(mean, 1e-6), 1.0 / c.max_gain, c.max_gain);
}

bool has_distortion(const CameraSpec& c) {
  return std::any_of(c.distortion.begin(), c.distortion.end(), [](double x) { return x != 0; });
}

/// Bilinear sample of an RGB8 image at (u, v) in pixel coordinates (pixel centres at integers).
void sample_rgb(const ColorImage& img, double u, double v, std::uint8_t* out) {
  if (u < -0.5 || v < -0.5 || u > img.width - 0.5 || v > img.height - 0.5) {
    out[0] = out[1] = out[2] = 0;
    return;
  }
  const int x0 = std::clamp(static_cast<int>(std::floor(u)), 0, img.width - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(v)), 0, img.height - 1);
  const int x1 = std::min(x0 + 1, img.width - 1), y1 = std::min(y0 + 1, img.height - 1);
  const double fx = std::clamp(u - x0, 0.0, 1.0), fy = std::clamp(v - y0, 0.0, 1.0);
  for (int c = 0; c < 3; ++c) {
    auto at = [&](int x, int y) { return img.rgb[static_cast<std::size_t>((y * img.width + x) * 3 + c)]; };
    const double top = at(x0, y0) * (1 - fx) + at(x1, y0) * fx;
    const double bottom = at(x0, y1) * (1 - fx) + at(x1, y1) * fx;
    out[c] = static_cast<std::uint8_t>(std::lround(top * (1 - fy) + bottom * fy));
  }
}

msg::Image make_image(const msg::Header& header, int w, int h, const char* encoding, int bytes_per_pixel) {
  msg::Image m;
  m.header = header;
  m.width = static_cast<std::uint32_t>(w);
  m.height = static_cast<std::uint32_t>(h);
  m.encoding = encoding;
  m.is_bigendian = 0;
  m.step = static_cast<std::uint32_t>(w * bytes_per_pixel);
  m.data.resize(static_cast<std::size_t>(m.step) * static_cast<std::size_t>(h));
  return m;
}

}  // namespace

Intrinsics camera_intrinsics(const CameraSpec& c) { return Intrinsics::from_hfov(c.width, c.height, c.hfov); }

CameraView camera_view(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec) {
  const int link = world.robot(robot).spec.link_index(spec.link);
  if (link < 0) throw Error({"", 0, "sensor " + spec.name}, "is mounted on link '" + spec.link + "', which the robot does not have");
  CameraView v;
  v.X_WC = state.robot(robot).X_WL[static_cast<std::size_t>(link)] * spec.X_LS;
  v.k = camera_intrinsics(spec.camera);
  v.near_clip = spec.camera.near_clip;
  v.far_clip = spec.camera.far_clip;
  return v;
}

msg::CameraInfo camera_info(const SensorSpec& spec, const msg::Header& header) {
  const Intrinsics k = camera_intrinsics(spec.camera);
  msg::CameraInfo ci;
  ci.header = header;
  ci.width = static_cast<std::uint32_t>(k.width);
  ci.height = static_cast<std::uint32_t>(k.height);
  ci.distortion_model = "plumb_bob";
  ci.d.assign(spec.camera.distortion.begin(), spec.camera.distortion.end());
  ci.k = {k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1};
  ci.p = {k.fx, 0, k.cx, 0, 0, k.fy, k.cy, 0, 0, 0, 1, 0};
  return ci;
}

msg::Image color_message(const ColorImage& image, const SensorSpec& spec, const msg::Header& header, Rng& rng) {
  const CameraSpec& c = spec.camera;
  msg::Image m = make_image(header, image.width, image.height, "rgb8", 3);
  if (has_distortion(c)) {
    // each output (distorted) pixel looks up where its ray lands in the pinhole rendering
    const Intrinsics k = camera_intrinsics(c);
    const BrownDistortion d = distortion_of(c);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const Vec2 xd((x - k.cx) / k.fx, (y - k.cy) / k.fy);
        const Vec2 xu = undistort(d, xd);
        sample_rgb(image, xu.x() * k.fx + k.cx, xu.y() * k.fy + k.cy, &m.data[static_cast<std::size_t>((y * image.width + x) * 3)]);
      }
    }
  } else {
    std::memcpy(m.data.data(), image.rgb.data(), m.data.size());
  }
  // exposure acts on linear light; noise on the encoded values (like sensor read noise), grown
  // by the gain an automatic exposure adds
  const double gain = c.auto_exposure ? auto_exposure_gain(m.data, c) : c.exposure;
  const double noise = c.noise.stddev * std::max(1.0, gain / c.exposure);
  if (gain != 1.0 || noise > 0) {
    std::uint8_t lut[256];
    for (int i = 0; i < 256; ++i) {
      lut[i] = static_cast<std::uint8_t>(std::lround(255 * linear_to_srgb(srgb_to_linear(i / 255.0) * gain)));
    }
    for (auto& px : m.data) {
      double v = lut[px];
      if (noise > 0) v += rng.normal(0, noise * 255);
      px = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
    }
  }
  return m;
}

msg::Image depth_message(const DepthImage& image, const SensorSpec& spec, const msg::Header& header, Rng& rng) {
  const CameraSpec& c = spec.camera;
  const bool mm = c.depth_encoding == "16UC1";
  msg::Image m = make_image(header, image.width, image.height, mm ? "16UC1" : "32FC1", mm ? 2 : 4);
  const bool noisy = c.noise.stddev > 0 || c.depth_noise_quadratic > 0;
  for (std::size_t i = 0; i < image.z.size(); ++i) {
    double z = image.z[i];
    const bool valid = std::isfinite(z) && z >= c.min_range && z <= c.max_range;
    if (valid && noisy) z += rng.normal(0, c.noise.stddev + c.depth_noise_quadratic * z * z);
    if (mm) {
      // 16UC1: millimetres, 0 for no data (the ROS convention)
      const std::uint16_t v = valid ? static_cast<std::uint16_t>(std::clamp(std::lround(z * 1000), 1L, 65535L)) : 0;
      std::memcpy(&m.data[i * 2], &v, 2);
    } else {
      const float v = valid ? static_cast<float>(z) : std::numeric_limits<float>::quiet_NaN();
      std::memcpy(&m.data[i * 4], &v, 4);
    }
  }
  return m;
}

msg::PointCloud2 depth_cloud(const msg::Image& depth, const SensorSpec& spec) {
  const Intrinsics k = camera_intrinsics(spec.camera);
  msg::PointCloud2 pc;
  pc.header = depth.header;
  pc.height = depth.height;
  pc.width = depth.width;
  pc.fields = {{"x", 0, msg::PointField::kFloat32, 1}, {"y", 4, msg::PointField::kFloat32, 1}, {"z", 8, msg::PointField::kFloat32, 1}};
  pc.point_step = 12;
  pc.row_step = 12 * depth.width;
  pc.is_dense = false;  // organised like the image: invalid pixels are NaN points
  pc.data.resize(static_cast<std::size_t>(pc.row_step) * depth.height);
  const bool mm = depth.encoding == "16UC1";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::uint32_t y = 0; y < depth.height; ++y) {
    for (std::uint32_t x = 0; x < depth.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * depth.width + x;
      float z;
      if (mm) {
        std::uint16_t v;
        std::memcpy(&v, &depth.data[i * 2], 2);
        z = v == 0 ? nan : v * 0.001f;
      } else {
        std::memcpy(&z, &depth.data[i * 4], 4);
      }
      float p[3] = {nan, nan, nan};
      if (std::isfinite(z)) {
        const Vec3 q = unproject(k, x, y, z);
        p[0] = static_cast<float>(q.x());
        p[1] = static_cast<float>(q.y());
        p[2] = static_cast<float>(q.z());
      }
      std::memcpy(&pc.data[i * 12], p, 12);
    }
  }
  return pc;
}

msg::Image thermal_mono16(const ThermalImage& image, const SensorSpec& spec, const msg::Header& header, Rng& rng) {
  const CameraSpec& c = spec.camera;
  msg::Image m = make_image(header, image.width, image.height, "mono16", 2);
  for (std::size_t i = 0; i < image.kelvin.size(); ++i) {
    const double t = add_noise(image.kelvin[i], c.noise, 0.0, rng);
    const std::uint16_t v = static_cast<std::uint16_t>(std::clamp(std::lround(t * 100), 0L, 65535L));
    std::memcpy(&m.data[i * 2], &v, 2);
  }
  return m;
}

msg::Image thermal_mono8(const msg::Image& mono16, const SensorSpec& spec) {
  const CameraSpec& c = spec.camera;
  msg::Image m = make_image(mono16.header, static_cast<int>(mono16.width), static_cast<int>(mono16.height), "mono8", 1);
  const double span = std::max(1e-6, c.mono8_max - c.mono8_min);
  for (std::size_t i = 0; i < m.data.size(); ++i) {
    std::uint16_t v;
    std::memcpy(&v, &mono16.data[i * 2], 2);
    m.data[i] = static_cast<std::uint8_t>(std::clamp(std::lround((kelvin_of_count(v) - c.mono8_min) / span * 255), 0L, 255L));
  }
  return m;
}

std::vector<int> victims_in_thermal_image(const World& world, const CameraView& view, const SensorSpec& spec,
                                          const msg::Image& mono16, double contrast) {
  std::vector<int> seen;
  const Pose3 X_OW = (view.X_WC * X_BO()).inverse();
  const int w = static_cast<int>(mono16.width), h = static_cast<int>(mono16.height);
  const double threshold = world.ambient_temperature + contrast;
  auto kelvin_at = [&](int x, int y) {
    std::uint16_t c;
    std::memcpy(&c, &mono16.data[(static_cast<std::size_t>(y) * mono16.width + static_cast<std::size_t>(x)) * 2], 2);
    return kelvin_of_count(c);
  };
  for (std::size_t v = 0; v < world.victims.size(); ++v) {
    bool warm = false;
    for (int part : world.victims[v].parts) {
      const Vec3 p_O = X_OW * world.statics[static_cast<std::size_t>(part)].X_WO.p;
      if (p_O.z() < spec.camera.min_range || p_O.z() > spec.camera.max_range) continue;
      const Vec2 uv = project(view.k, p_O);
      const int cx = static_cast<int>(std::lround(uv.x())), cy = static_cast<int>(std::lround(uv.y()));
      for (int y = cy - 1; y <= cy + 1 && !warm; ++y) {
        for (int x = cx - 1; x <= cx + 1 && !warm; ++x) {
          if (x >= 0 && y >= 0 && x < w && y < h && kelvin_at(x, y) >= threshold) warm = true;
        }
      }
      if (warm) break;
    }
    if (warm) seen.push_back(static_cast<int>(v));
  }
  return seen;
}

// decoders: each checks the encoding and size, then reads pixels in host byte order

namespace {

/// Checks a message's size and encoding; returns its bytes per pixel.
std::size_t check_image(const msg::Image& m, std::initializer_list<const char*> encodings, std::size_t bytes, const char* who) {
  bool known = false;
  for (const char* e : encodings) known = known || m.encoding == e;
  if (!known) throw Error(SourceRef{"", 0, who}, fmt::format("cannot decode an image with encoding '{}'", m.encoding));
  if (m.step < m.width * bytes || m.data.size() < static_cast<std::size_t>(m.height) * m.step) {
    throw Error(SourceRef{"", 0, who}, fmt::format("a {}x{} {} image needs {} bytes per row and {} rows of data", m.width, m.height,
                                                   m.encoding, m.width * bytes, m.height));
  }
  return bytes;
}

/// The pixel at column x, row y of a message as an unsigned or float value, in host byte order.
template <class T>
T pixel(const msg::Image& m, std::uint32_t x, std::uint32_t y) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &m.data[static_cast<std::size_t>(y) * m.step + x * sizeof(T)], sizeof(T));
  if (m.is_bigendian) std::reverse(std::begin(b), std::end(b));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

}  // namespace

ColorImage color_image_of(const msg::Image& m) {
  check_image(m, {"rgb8", "bgr8"}, 3, "color_image_of");
  ColorImage img;
  img.width = static_cast<int>(m.width);
  img.height = static_cast<int>(m.height);
  img.rgb.resize(static_cast<std::size_t>(m.width) * m.height * 3);
  const bool bgr = m.encoding == "bgr8";
  for (std::uint32_t y = 0; y < m.height; ++y) {
    for (std::uint32_t x = 0; x < m.width; ++x) {
      const std::uint8_t* p = &m.data[static_cast<std::size_t>(y) * m.step + x * 3];
      std::uint8_t* q = &img.rgb[(static_cast<std::size_t>(y) * m.width + x) * 3];
      q[0] = p[bgr ? 2 : 0];
      q[1] = p[1];
      q[2] = p[bgr ? 0 : 2];
    }
  }
  return img;
}

DepthImage depth_image_of(const msg::Image& m) {
  const bool mm = m.encoding == "16UC1";
  check_image(m, {"32FC1", "16UC1"}, mm ? 2 : 4, "depth_image_of");
  DepthImage img;
  img.width = static_cast<int>(m.width);
  img.height = static_cast<int>(m.height);
  img.z.resize(static_cast<std::size_t>(m.width) * m.height);
  const float none = std::numeric_limits<float>::infinity();
  for (std::uint32_t y = 0; y < m.height; ++y) {
    for (std::uint32_t x = 0; x < m.width; ++x) {
      float z;
      if (mm) {
        const auto v = pixel<std::uint16_t>(m, x, y);
        z = v == 0 ? none : v * 0.001f;
      } else {
        z = pixel<float>(m, x, y);
        if (std::isnan(z)) z = none;
      }
      img.z[static_cast<std::size_t>(y) * m.width + x] = z;
    }
  }
  return img;
}

ThermalImage thermal_image_of(const msg::Image& m) {
  check_image(m, {"mono16"}, 2, "thermal_image_of");
  ThermalImage img;
  img.width = static_cast<int>(m.width);
  img.height = static_cast<int>(m.height);
  img.kelvin.resize(static_cast<std::size_t>(m.width) * m.height);
  for (std::uint32_t y = 0; y < m.height; ++y) {
    for (std::uint32_t x = 0; x < m.width; ++x) {
      img.kelvin[static_cast<std::size_t>(y) * m.width + x] = pixel<std::uint16_t>(m, x, y) * 0.01f;
    }
  }
  return img;
}

}  // namespace rescuesim
