// load_mesh: checks the file, reads it with assimp, places every node's triangles in metres with
// z up, welds them, and picks a colour. Assimp logs nothing unless a DefaultLogger is created,
// which rescuesim never does, so the library stays silent.

#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "import/mesh/mesh.h"
#include "import/mesh/mesh_assimp.h"
#include "import/mesh/mesh_detail.h"

namespace rescuesim {

namespace {

/// The file being loaded and who named it, for error messages.
struct LoadContext {
  std::filesystem::path file;
  SourceRef named_by;

  /// Throws an Error located at the referring element (or the file) whose text names the file.
  [[noreturn]] void fail(const std::string& problem) const {
    const bool referred = !named_by.file.empty() || !named_by.element.empty();
    throw Error(referred ? named_by : SourceRef{file.string(), 0, ""}, "mesh file \"" + file.string() + "\" " + problem);
  }
};

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// Our name of the format from the file extension, or "" when it is not one we support.
std::string format_of(const std::filesystem::path& file) {
  const std::string ext = lowercase(file.extension().string());
  if (ext == ".stl") return "stl";
  if (ext == ".dae") return "collada";
  if (ext == ".obj") return "obj";
  if (ext == ".gltf" || ext == ".glb") return "gltf";
  return "";
}

std::string limit_message(std::uint64_t count, std::size_t limit) {
  std::ostringstream s;
  s << "has " << count << " triangles, more than the " << limit
    << " allowed; simplify it (e.g. Blender's Decimate modifier or meshlab) or use a primitive";
  return s.str();
}

/// A binary STL is an 80-byte header, a uint32 triangle count and 50 bytes per triangle. When the
/// file's size fits that layout, the count is checked here, before assimp allocates anything. Assimp
/// 5.2 does the size test in 32 bits, so a file that matches only after wrap-around is refused too.
void check_binary_stl(const LoadContext& ctx, std::uintmax_t size, std::size_t max_triangles) {
  if (size < 84) return;
  std::ifstream in(ctx.file, std::ios::binary);
  unsigned char header[84];
  if (!in.read(reinterpret_cast<char*>(header), sizeof header)) ctx.fail("cannot be read");
  const std::uint64_t count = std::uint64_t{header[80]} | std::uint64_t{header[81]} << 8 | std::uint64_t{header[82]} << 16 |
                              std::uint64_t{header[83]} << 24;
  const std::uint64_t expected = 84 + 50 * count;
  const bool binary = expected == size;
  const bool assimp_thinks_binary = static_cast<std::uint32_t>(expected) == static_cast<std::uint32_t>(size);
  if (binary && count == 0) ctx.fail("has no triangles (a binary STL with a count of 0)");
  if (binary && count > max_triangles) ctx.fail(limit_message(count, max_triangles));
  if (!binary && assimp_thinks_binary) {
    ctx.fail("is a binary STL whose header claims " + std::to_string(count) + " triangles, which does not match its size of " +
             std::to_string(size) + " bytes");
  }
}

/// True when the importer assimp chose lists `extension` (no dot) among its own.
bool importer_handles(const Assimp::Importer& importer, const std::string& extension, std::string& importer_name) {
  const int index = importer.GetPropertyInteger("importerIndex", -1);
  const aiImporterDesc* desc = index >= 0 ? importer.GetImporterInfo(static_cast<std::size_t>(index)) : nullptr;
  if (desc == nullptr) return true;  // assimp did not say; trust the extension
  importer_name = desc->mName;
  std::istringstream extensions(desc->mFileExtensions);
  for (std::string e; extensions >> e;) {
    if (lowercase(e) == extension) return true;
  }
  return false;
}

/// The loader's frame fix: assimp 5.2 already scales a COLLADA file by its <unit meter> and turns
/// its <up_axis> into y up (it multiplies the root node); glTF is y up by its specification. Both
/// are turned to z up, (x, y, z) -> (x, -z, y), as ROS tools do. STL and OBJ have no frame of
/// their own and are taken as they are. The user's scale then applies per axis.
Eigen::Matrix4d frame_fix(const std::string& format, const Vec3& scale) {
  Eigen::Matrix4d X = Eigen::Matrix4d::Identity();
  if (format == "collada" || format == "gltf") {
    X.topLeftCorner<3, 3>() << 1, 0, 0,
                               0, 0, -1,
                               0, 1, 0;
  }
  return scale.homogeneous().asDiagonal() * X;
}

}  // namespace

LoadedMesh load_mesh(const std::filesystem::path& file, const MeshLoadOptions& options, const SourceRef& named_by) {
  const LoadContext ctx{file, named_by};

  // the file must exist, be a regular file we can open, and have an extension we support
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) ctx.fail("does not exist");
  if (!std::filesystem::is_regular_file(status)) ctx.fail("is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) ctx.fail("cannot be read: " + ec.message());
  if (!std::ifstream(file, std::ios::binary)) ctx.fail("cannot be opened for reading");
  const std::string format = format_of(file);
  if (format.empty()) {
    ctx.fail("has an unsupported extension \"" + file.extension().string() + "\"; supported are .stl, .dae, .obj, .gltf and .glb");
  }
  if (!options.scale.allFinite() || (options.scale.array() == 0.0).any()) ctx.fail("cannot be scaled by zero or a non-finite factor");
  if (format == "stl") check_binary_stl(ctx, size, options.max_triangles);

  // read without post-processing first, so the triangle count is checked before any work on it
  Assimp::Importer importer;
  const aiScene* raw = importer.ReadFile(file.string(), 0);
  if (raw == nullptr) ctx.fail("is not a readable " + format + " file: " + importer.GetErrorString());
  std::string importer_name;
  const std::string extension = lowercase(file.extension().string()).substr(1);
  if (!importer_handles(importer, extension, importer_name)) {
    ctx.fail("is not a " + format + " file (assimp recognised it as " + importer_name + ")");
  }
  const std::uint64_t count = mesh_detail::count_triangles(*raw);
  if (count == 0) ctx.fail("has no triangles");
  if (count > options.max_triangles) ctx.fail(limit_message(count, options.max_triangles));

  // then fan polygons into triangles and share equal vertices, validating assimp's structures
  const aiScene* scene =
      importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr) ctx.fail("is not a valid " + format + " file: " + importer.GetErrorString());

  // every node's triangles in metres, z up, user-scaled; a mirroring scale keeps them outward
  mesh_detail::TriangleSoup soup = mesh_detail::scene_triangles(*scene, frame_fix(format, options.scale));
  for (const Vec3& v : soup.vertices) {
    if (!v.allFinite()) ctx.fail("has a vertex with a coordinate that is not a finite number");
  }

  // one vertex per position, so the mesh is closed where the file meant it to be
  LoadedMesh out;
  out.format = format;
  std::vector<int> kept;
  out.mesh = mesh_detail::weld(soup.vertices, soup.triangles, &kept);
  if (out.mesh.triangles.empty()) ctx.fail("has no triangles with three distinct corners");
  const bool gltf2 = importer_name.find("glTF2") != std::string::npos;
  out.color = mesh_detail::first_diffuse_color(*scene, gltf2, format == "gltf");
  // the texture it names, beside the file (COLLADA may write file:// URIs); the image is only
  // found here, decoded by whoever draws it
  out.texture = mesh_detail::first_diffuse_texture(*scene);
  if (!out.texture.empty() && soup.all_uvs) {
    std::string name = out.texture;
    if (name.rfind("file://", 0) == 0) name = name.substr(7);
    std::replace(name.begin(), name.end(), '\\', '/');  // Windows-made files
    std::filesystem::path image = name;
    if (image.is_relative()) image = file.parent_path() / image;
    std::error_code ec;
    if (std::filesystem::is_regular_file(image, ec)) {
      auto surface = std::make_shared<SurfaceImage>();
      surface->file = std::filesystem::absolute(image).lexically_normal().string();
      surface->corner_uvs.reserve(kept.size());
      for (int t : kept) surface->corner_uvs.push_back(soup.corner_uvs[static_cast<std::size_t>(t)]);
      out.image = std::move(surface);
    }
  }
  return out;
}

}  // namespace rescuesim
