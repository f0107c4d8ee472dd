#pragma once
// Fixture files for the mesh tests (and the URDF tests, tests/import/urdf), written by the tests
// themselves: a temporary folder per test, and small writers for binary STL and base64 (glTF's
// embedded buffers).

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "world/geometry.h"

namespace rescuesim::mesh_test {

/// A fresh folder under the system temp folder, removed with its contents afterwards.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string test = info ? std::string(info->test_suite_name()) + "_" + info->name() : "none";
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
            ("rescuesim_" + test + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + std::to_string(stamp));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  /// Writes `bytes` to `name` (folders created as needed) in this folder; returns its path.
  std::filesystem::path write(const std::filesystem::path& name, const std::string& bytes) const {
    const auto file = path_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file;
  }

 private:
  std::filesystem::path path_;
};

/// Appends the little-endian bytes of a trivially copyable value (x86 and ARM are little-endian).
template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

/// A binary STL of the mesh: 80-byte header, uint32 count, 50 bytes per triangle.
inline std::string binary_stl(const TriangleMesh& m) {
  std::string out(80, ' ');
  out.replace(0, 15, "binary cube stl");
  put(out, static_cast<std::uint32_t>(m.triangles.size()));
  for (const auto& t : m.triangles) {
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 n = (b - a).cross(c - a).normalized();
    for (const Vec3& v : {n, a, b, c}) {
      for (int k = 0; k < 3; ++k) put(out, static_cast<float>(v[k]));
    }
    put(out, std::uint16_t{0});
  }
  return out;
}

/// An ASCII STL of the mesh.
inline std::string ascii_stl(const TriangleMesh& m) {
  std::string out = "solid cube\n";
  for (const auto& t : m.triangles) {
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 n = (b - a).cross(c - a).normalized();
    out += "  facet normal " + std::to_string(n.x()) + " " + std::to_string(n.y()) + " " + std::to_string(n.z()) + "\n    outer loop\n";
    for (const Vec3* v : {&a, &b, &c}) {
      out += "      vertex " + std::to_string(v->x()) + " " + std::to_string(v->y()) + " " + std::to_string(v->z()) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid cube\n";
}

/// Standard base64 with padding.
inline std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t chunk = 0;
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    for (std::size_t k = 0; k < 3; ++k) chunk = chunk << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? digits[(chunk >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

/// The axis-aligned extent of a mesh's vertices.
inline Vec3 extent(const TriangleMesh& m) {
  Vec3 lo = m.vertices.front(), hi = m.vertices.front();
  for (const Vec3& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return hi - lo;
}

/// True when the mesh has a vertex within `tol` of p.
inline bool has_vertex(const TriangleMesh& m, const Vec3& p, double tol = 1e-9) {
  for (const Vec3& v : m.vertices) {
    if ((v - p).norm() <= tol) return true;
  }
  return false;
}

}  // namespace rescuesim::mesh_test
