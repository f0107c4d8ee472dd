// load_mesh against coordinates worked out by hand: STL (ASCII and binary) scaled to millimetres,
// COLLADA's <unit> and <up_axis> and node transforms, OBJ with its .mtl colour, and glTF / GLB
// turned from y up to z up.

#include <gtest/gtest.h>

#include <cmath>

#include "import/mesh/mesh.h"
#include "import/mesh/mesh_test_files.h"

namespace rescuesim {
namespace {

using mesh_test::TempDir;

/// Assimp stores coordinates and transforms in float, so results carry float rounding (~1e-7).
void expect_vec(const Vec3& a, const Vec3& b, double tol = 1e-6) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
  EXPECT_NEAR(a.z(), b.z(), tol);
}

/// A COLLADA file holding one triangle with corners (0, 100, 0), (100, 0, 0), (0, 0, 100) in file
/// units, with a red diffuse material, placed by `node` (which must contain "GEOMETRY").
std::string collada(const std::string& up_axis, const std::string& meter, const std::string& node = "GEOMETRY") {
  const std::string geometry = R"(<instance_geometry url="#tri"><bind_material><technique_common>
      <instance_material symbol="mat" target="#red"/></technique_common></bind_material></instance_geometry>)";
  std::string placed = node;
  placed.replace(placed.find("GEOMETRY"), 8, geometry);
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter=")" + meter + R"(" name="unit"/><up_axis>)" + up_axis + R"(</up_axis></asset>
  <library_effects><effect id="red-fx"><profile_COMMON><technique sid="common"><lambert>
    <diffuse><color>0.8 0.1 0.2 1</color></diffuse></lambert></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="red" name="red"><instance_effect url="#red-fx"/></material></library_materials>
  <library_geometries><geometry id="tri" name="tri"><mesh>
    <source id="tri-pos"><float_array id="tri-pos-array" count="9">0 100 0 100 0 0 0 0 100</float_array>
      <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
    <triangles material="mat" count="1"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="top" name="top">)" +
         placed + R"(</node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

TEST(MeshLoad, AsciiStlCubeScaledToMillimetres) {
  TempDir dir;
  const auto file = dir.write("cube.stl", mesh_test::ascii_stl(mesh_of(Geometry::box({1, 1, 1}))));
  MeshLoadOptions o;
  o.scale = {0.001, 0.001, 0.001};
  const LoadedMesh m = load_mesh(file, o);
  EXPECT_EQ(m.format, "stl");
  EXPECT_EQ(m.mesh.triangles.size(), 12u);
  EXPECT_EQ(m.mesh.vertices.size(), 8u);  // STL repeats corners per facet; they are welded
  expect_vec(mesh_test::extent(m.mesh), {0.001, 0.001, 0.001}, 1e-10);
  EXPECT_TRUE(mesh_test::has_vertex(m.mesh, {-0.0005, -0.0005, -0.0005}, 1e-10));
  // closed and outward: the divergence theorem gives the cube's volume with a positive sign
  EXPECT_NEAR(mass_properties(m.mesh).volume, 1e-9, 1e-15);
  EXPECT_FALSE(m.color.has_value());
}

TEST(MeshLoad, BinaryStlCubeScaledToMillimetres) {
  TempDir dir;
  const auto file = dir.write("cube.STL", mesh_test::binary_stl(mesh_of(Geometry::box({1, 1, 1}))));
  MeshLoadOptions o;
  o.scale = {0.001, 0.001, 0.001};
  const LoadedMesh m = load_mesh(file, o);
  EXPECT_EQ(m.format, "stl");
  EXPECT_EQ(m.mesh.triangles.size(), 12u);
  EXPECT_EQ(m.mesh.vertices.size(), 8u);
  expect_vec(mesh_test::extent(m.mesh), {0.001, 0.001, 0.001}, 1e-10);
  EXPECT_NEAR(mass_properties(m.mesh).volume, 1e-9, 1e-15);
}

TEST(MeshLoad, ColladaCentimetresYUpBecomeMetresZUp) {
  // unit 0.01 m; Y_UP turned to z up: file (x, y, z) -> 0.01 * (x, -z, y)
  TempDir dir;
  const LoadedMesh m = load_mesh(dir.write("tri.dae", collada("Y_UP", "0.01")));
  EXPECT_EQ(m.format, "collada");
  ASSERT_EQ(m.mesh.vertices.size(), 3u);
  expect_vec(m.mesh.vertices[0], {0, 0, 1});   // file (0, 100, 0): up
  expect_vec(m.mesh.vertices[1], {1, 0, 0});   // file (100, 0, 0)
  expect_vec(m.mesh.vertices[2], {0, -1, 0});  // file (0, 0, 100): toward the viewer
  ASSERT_TRUE(m.color.has_value());
  expect_vec(*m.color, {0.8, 0.1, 0.2}, 1e-6);
}

TEST(MeshLoad, ColladaZUpIsKeptAsWritten) {
  TempDir dir;
  const LoadedMesh m = load_mesh(dir.write("tri.dae", collada("Z_UP", "0.01")));
  ASSERT_EQ(m.mesh.vertices.size(), 3u);
  expect_vec(m.mesh.vertices[0], {0, 1, 0});
  expect_vec(m.mesh.vertices[1], {1, 0, 0});
  expect_vec(m.mesh.vertices[2], {0, 0, 1});
}

TEST(MeshLoad, ColladaNodeTransformsApplyParentFirst) {
  // the parent lifts by 500 units, the child turns 90 degrees about z: file (100, 0, 0) ->
  // (0, 100, 0) -> (0, 100, 500) -> metres (0, 1, 5)
  TempDir dir;
  const std::string node = R"(<translate>0 0 500</translate><node id="child"><rotate>0 0 1 90</rotate>GEOMETRY</node>)";
  const LoadedMesh m = load_mesh(dir.write("moved.dae", collada("Z_UP", "0.01", node)));
  ASSERT_EQ(m.mesh.vertices.size(), 3u);
  expect_vec(m.mesh.vertices[0], {-1, 0, 5});  // file (0, 100, 0) turned to (-100, 0, 0)
  expect_vec(m.mesh.vertices[1], {0, 1, 5});
  expect_vec(m.mesh.vertices[2], {0, 0, 6});
}

TEST(MeshLoad, ScaleAppliesPerAxisAfterTheUnitAndUpAxis) {
  TempDir dir;
  MeshLoadOptions o;
  o.scale = {1, 2, 3};
  const LoadedMesh m = load_mesh(dir.write("tri.dae", collada("Y_UP", "0.01")), o);
  expect_vec(m.mesh.vertices[0], {0, 0, 3});
  expect_vec(m.mesh.vertices[1], {1, 0, 0});
  expect_vec(m.mesh.vertices[2], {0, -2, 0});
}

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

TEST(MeshLoad, MirroringScaleKeepsTheWindingsSide) {
  // a mirror turns a mesh inside out; the loader re-winds it, so the signed volume keeps its sign
  const TriangleMesh box = mesh_of(Geometry::box({1, 2, 3}));
  TempDir dir;
  const auto file = dir.write("box.stl", mesh_test::binary_stl(box));
  MeshLoadOptions o;
  o.scale = {-1, 1, 1};
  EXPECT_NEAR(signed_volume(load_mesh(file).mesh), signed_volume(box), 1e-9);
  EXPECT_NEAR(signed_volume(load_mesh(file, o).mesh), signed_volume(box), 1e-9);
  EXPECT_NEAR(std::abs(signed_volume(box)), 6.0, 1e-12);
}

TEST(MeshLoad, ObjCubeWithMtlColour) {
  // faces counter-clockwise seen from outside; six quads become twelve triangles
  TempDir dir;
  dir.write("cube.mtl", "newmtl blue\nKd 0.1 0.2 0.9\n");
  const auto file = dir.write("cube.obj", R"(mtllib cube.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
usemtl blue
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)");
  const LoadedMesh m = load_mesh(file);
  EXPECT_EQ(m.format, "obj");
  EXPECT_EQ(m.mesh.triangles.size(), 12u);
  EXPECT_EQ(m.mesh.vertices.size(), 8u);
  EXPECT_TRUE(mesh_test::has_vertex(m.mesh, {1, 1, 1}));
  EXPECT_TRUE(mesh_test::has_vertex(m.mesh, {0, 0, 0}));
  const MassProperties mp = mass_properties(m.mesh);
  EXPECT_NEAR(mp.volume, 1.0, 1e-9);
  expect_vec(mp.centroid, {0.5, 0.5, 0.5});
  ASSERT_TRUE(m.color.has_value());
  expect_vec(*m.color, {0.1, 0.2, 0.9}, 1e-6);
}

TEST(MeshLoad, ObjWithoutMaterialHasNoColour) {
  TempDir dir;
  const LoadedMesh m = load_mesh(dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(m.mesh.triangles.size(), 1u);
  EXPECT_FALSE(m.color.has_value());
}

/// The bytes of one triangle (0,0,0), (1,0,0), (0,1,0) as glTF accessors: 36 bytes of float
/// positions, then 3 uint16 indices padded to 8 bytes.
std::string triangle_buffer() {
  std::string b;
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) mesh_test::put(b, f);
  for (std::uint16_t i : {0, 1, 2, 0}) mesh_test::put(b, i);
  return b;
}

/// glTF JSON for that triangle in a node moved by (0, 0, 2), with an optional base colour and an
/// optional buffer uri (none: the GLB's own binary chunk).
std::string gltf_json(bool with_material, const std::string& uri) {
  const std::string buffer = uri.empty() ? R"({"byteLength":44})" : R"({"byteLength":44,"uri":")" + uri + R"("})";
  return std::string(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)") +
         R"("nodes":[{"mesh":0,"translation":[0,0,2]}],)" +
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1)" + (with_material ? R"(,"material":0)" : "") + "}]}]," +
         (with_material ? R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1.0,1.0]}}],)" : "") +
         R"("buffers":[)" + buffer + "]," +
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)" +
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)" +
         R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
}

/// sRGB encoding of a linear value, as glTF's linear baseColorFactor is reported in sRGB.
double srgb(double c) { return 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

TEST(MeshLoad, GltfEmbeddedBufferIsTurnedToZUp) {
  // glTF is y up: (x, y, z) -> (x, -z, y); the node's (0, 0, 2) becomes (0, -2, 0)
  TempDir dir;
  const std::string uri = "data:application/octet-stream;base64," + mesh_test::base64(triangle_buffer());
  const LoadedMesh m = load_mesh(dir.write("tri.gltf", gltf_json(true, uri)));
  EXPECT_EQ(m.format, "gltf");
  ASSERT_EQ(m.mesh.vertices.size(), 3u);
  expect_vec(m.mesh.vertices[0], {0, -2, 0});
  expect_vec(m.mesh.vertices[1], {1, -2, 0});
  expect_vec(m.mesh.vertices[2], {0, -2, 1});
  ASSERT_TRUE(m.color.has_value());
  expect_vec(*m.color, {srgb(0.5), srgb(0.25), 1.0}, 1e-6);
}

TEST(MeshLoad, GlbBinaryChunkLoadsAndHasNoColourWithoutMaterial) {
  // GLB: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with zeros
  std::string json = gltf_json(false, "");
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string bin = triangle_buffer();
  std::string glb = "glTF";
  mesh_test::put(glb, std::uint32_t{2});
  mesh_test::put(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  mesh_test::put(glb, static_cast<std::uint32_t>(json.size()));
  glb += "JSON" + json;
  mesh_test::put(glb, static_cast<std::uint32_t>(bin.size()));
  glb += std::string("BIN\0", 4) + bin;
  TempDir dir;
  const LoadedMesh m = load_mesh(dir.write("tri.glb", glb));
  EXPECT_EQ(m.format, "gltf");
  ASSERT_EQ(m.mesh.vertices.size(), 3u);
  expect_vec(m.mesh.vertices[2], {0, -2, 1});
  EXPECT_FALSE(m.color.has_value());  // assimp's stand-in white material is not reported
}

}  // namespace
}  // namespace rescuesim
