// load_mesh refusing bad files with an Error that names the file (and whoever referred to it):
// missing, garbage, empty, too many triangles (checked from a binary STL's header, cheaply).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "import/mesh/mesh.h"
#include "import/mesh/mesh_test_files.h"

namespace rescuesim {
namespace {

using mesh_test::TempDir;
using ::testing::HasSubstr;

/// The Error load_mesh throws for `file`; fails the test when it throws nothing.
Error load_error(const std::filesystem::path& file, const MeshLoadOptions& o = {}, const SourceRef& named_by = {}) {
  try {
    load_mesh(file, o, named_by);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no Error for " << file;
  return Error("none");
}

TEST(MeshLoadErrors, MissingFileIsNamed) {
  TempDir dir;
  const auto file = dir.path() / "nowhere.stl";
  const Error e = load_error(file);
  EXPECT_THAT(e.what(), HasSubstr(file.string()));
  EXPECT_THAT(e.what(), HasSubstr("does not exist"));
  EXPECT_EQ(e.where().file, file.string());
}

TEST(MeshLoadErrors, TheReferringElementIsQuoted) {
  TempDir dir;
  const auto file = dir.path() / "meshes" / "arm.dae";
  const Error e = load_error(file, {}, SourceRef{"robot.urdf", 12, "<mesh filename>"});
  EXPECT_THAT(std::string(e.what()), ::testing::StartsWith("robot.urdf:12: <mesh filename>: "));
  EXPECT_THAT(e.what(), HasSubstr(file.string()));
  EXPECT_EQ(e.where().line, 12);
}

TEST(MeshLoadErrors, GarbageNamedStlOrDaeIsRefusedWithoutACrash) {
  TempDir dir;
  std::mt19937 rng(20240601);
  for (int round = 0; round < 20; ++round) {
    std::string garbage(200, '\0');
    for (char& c : garbage) c = static_cast<char>(rng() & 0xff);
    for (const std::string name : {"x.stl", "x.dae"}) {
      const auto file = dir.write(name, garbage);
      const Error e = load_error(file);
      EXPECT_THAT(e.what(), HasSubstr(file.string())) << "round " << round;
    }
    // other formats may read garbage as an empty file, but never crash or throw anything else
    for (const std::string name : {"x.obj", "x.gltf", "x.glb"}) {
      try {
        load_mesh(dir.write(name, garbage));
      } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr(name));
      }
    }
  }
}

TEST(MeshLoadErrors, AssimpsReasonIsIncluded) {
  TempDir dir;
  const Error e = load_error(dir.write("x.dae", "this is not xml"));
  EXPECT_THAT(e.what(), HasSubstr("not a readable collada file: "));
}

TEST(MeshLoadErrors, HugeBinaryStlIsRefusedFromItsHeader) {
  // a sparse file: the header claims 2,000,001 triangles and the size matches, but the triangles
  // are never read (that would take seconds and half a gigabyte)
  TempDir dir;
  std::string header(80, ' ');
  mesh_test::put(header, std::uint32_t{2'000'001});
  const auto file = dir.write("huge.stl", header);
  std::filesystem::resize_file(file, 84 + 50ull * 2'000'001);
  const auto start = std::chrono::steady_clock::now();
  const Error e = load_error(file);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  EXPECT_THAT(e.what(), HasSubstr("has 2000001 triangles, more than the 2000000 allowed"));
  EXPECT_THAT(e.what(), HasSubstr("Decimate"));
}

TEST(MeshLoadErrors, TriangleLimitAppliesToEveryFormat) {
  TempDir dir;
  MeshLoadOptions o;
  o.max_triangles = 11;
  const auto cube = mesh_of(Geometry::box({1, 1, 1}));
  EXPECT_THAT(load_error(dir.write("a.stl", mesh_test::ascii_stl(cube)), o).what(), HasSubstr("has 12 triangles, more than the 11"));
  EXPECT_THAT(load_error(dir.write("b.stl", mesh_test::binary_stl(cube)), o).what(), HasSubstr("has 12 triangles, more than the 11"));
  o.max_triangles = 12;
  EXPECT_EQ(load_mesh(dir.write("c.stl", mesh_test::binary_stl(cube)), o).mesh.triangles.size(), 12u);
}

TEST(MeshLoadErrors, EmptyStlIsRefused) {
  TempDir dir;
  const auto ascii = dir.write("empty.stl", "solid empty\nendsolid empty\n");
  EXPECT_THAT(load_error(ascii).what(), HasSubstr(ascii.string()));
  std::string binary(80, ' ');
  mesh_test::put(binary, std::uint32_t{0});
  const auto file = dir.write("empty_binary.stl", binary);
  EXPECT_THAT(load_error(file).what(), HasSubstr("has no triangles"));
}

TEST(MeshLoadErrors, ObjWithOnlyLinesHasNoTriangles) {
  TempDir dir;
  const auto file = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  EXPECT_THAT(load_error(file).what(), HasSubstr("has no triangles"));
}

TEST(MeshLoadErrors, UnsupportedExtensionsAndDirectoriesAreRefused) {
  TempDir dir;
  EXPECT_THAT(load_error(dir.write("part.ply", "ply\n")).what(), HasSubstr("unsupported extension \".ply\""));
  std::filesystem::create_directories(dir.path() / "folder.stl");
  EXPECT_THAT(load_error(dir.path() / "folder.stl").what(), HasSubstr("is not a regular file"));
}

TEST(MeshLoadErrors, ZeroScaleIsRefused) {
  TempDir dir;
  MeshLoadOptions o;
  o.scale = {1, 0, 1};
  const auto file = dir.write("cube.stl", mesh_test::binary_stl(mesh_of(Geometry::box({1, 1, 1}))));
  EXPECT_THAT(load_error(file, o).what(), HasSubstr("scaled by zero"));
}

}  // namespace
}  // namespace rescuesim
