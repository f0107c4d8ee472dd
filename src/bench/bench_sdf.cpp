#include "bench/bench_sdf.h"

#include <algorithm>
#include <cstdio>

#include "bench/bench_figures.h"
#include "import/mesh/mesh.h"
#include "import/sdf/sdf_import.h"
#include "raycast/bench/raycast_bench.h"

namespace rescuesim::bench {

using json = nlohmann::ordered_json;

namespace {

/// The faces of an axis-aligned box (full extents `size`, centred at `c`), each cut into an
/// n x n grid of quads: many triangles on exactly the box's surface.
void add_fine_box(TriangleMesh& m, const Vec3& c, const Vec3& size, int n) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (const double side : {-1.0, 1.0}) {
      const int base = static_cast<int>(m.vertices.size());
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          Vec3 p = c;
          p[axis] += side * size[axis] / 2;
          p[u] += (static_cast<double>(i) / n - 0.5) * size[u];
          p[v] += (static_cast<double>(j) / n - 0.5) * size[v];
          m.vertices.push_back(p);
        }
      }
      const auto at = [&](int i, int j) { return base + i * (n + 1) + j; };
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          // counter-clockwise seen from outside: (u, v, axis) is right-handed, so +side faces keep the order
          if (side > 0) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
          } else {
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
            m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
          }
        }
      }
    }
  }
}

/// A 10 x 10 m room with 16 pillars: as primitives (boxes), or as one static mesh of the same
/// surfaces cut to at least `min_triangles` triangles.
World room(bool as_mesh, std::size_t min_triangles) {
  std::vector<std::pair<Vec3, Vec3>> boxes;  // centre, size
  boxes.push_back({{5, -0.1, 1}, {10.4, 0.2, 2}});
  boxes.push_back({{5, 10.1, 1}, {10.4, 0.2, 2}});
  boxes.push_back({{-0.1, 5, 1}, {0.2, 10, 2}});
  boxes.push_back({{10.1, 5, 1}, {0.2, 10, 2}});
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) boxes.push_back({{1.75 + 2.2 * i, 1.75 + 2.2 * j, 1}, {0.3, 0.3, 2}});
  }
  WorldSpec w;
  w.name = as_mesh ? "room_mesh" : "room_primitives";
  w.materials = default_materials();
  w.floor_max = {10, 10};
  if (as_mesh) {
    // 12 triangles x n^2 per box
    int n = 1;
    while (boxes.size() * 12 * static_cast<std::size_t>(n * n) < min_triangles) ++n;
    TriangleMesh m;
    for (const auto& [c, size] : boxes) add_fine_box(m, c, size, n);
    SolidSpec s;
    s.name = "room";
    s.geometry = Geometry::triangles(std::move(m));
    w.solids.push_back(std::move(s));
  } else {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      SolidSpec s;
      s.name = "box_" + std::to_string(i);
      s.geometry = Geometry::box(boxes[i].second);
      s.X_WS.p = boxes[i].first;
      w.solids.push_back(std::move(s));
    }
  }
  return compile_world(w, {});
}

}  // namespace

json bench_sdf(const std::filesystem::path& world_file, const std::vector<std::filesystem::path>& resource_paths, double seconds) {
  json j;
  if (!std::filesystem::exists(world_file)) {
    j["load"] = {{"skipped", world_file.string() + " not found (run the bench from the source folder, or give --sdf-world)"}};
  } else {
    std::fprintf(stderr, "bench: SDF load ...\n");
    SdfOptions o;
    o.resolver = ResourceResolver(resource_paths);
    SdfWorld w;
    std::vector<double> parse;
    const double load = median_seconds(5, [&] {
      w = load_sdf_world(world_file, o);
      parse.push_back(w.parse_seconds);
    });
    std::sort(parse.begin(), parse.end());
    const double meshes = median_seconds(5, [&] {
      for (const auto& m : w.meshes) load_mesh(m.file);
    });
    long triangles = 0;
    for (const auto& m : w.meshes) triangles += m.triangles;
    // the baseline is what the libraries cost on their own: sdformat parsing the file and its
    // includes, and assimp loading the mesh files; the ratio is the importer's own work on top
    const double libraries = parse[parse.size() / 2] + meshes;
    j["load"] = ratio_figure(load * 1e3, "ms", libraries * 1e3,
                             "sdformat parsing the same file and its includes plus assimp loading its mesh files, medians of 5");
    j["load"]["sdformat_ms"] = parse[parse.size() / 2] * 1e3;
    j["load"]["mesh_files_ms"] = meshes * 1e3;
    j["load"]["world"] = world_file.string();
    j["load"]["models"] = w.models.size();
    j["load"]["mesh_files"] = w.meshes.size();
    j["load"]["triangles"] = triangles;
  }
  std::fprintf(stderr, "bench: lidar rays through a 100k-triangle static mesh and through primitives ...\n");
  const World mesh = room(true, 100'000), boxes = room(false, 0);
  const Vec3 origin(0.9, 0.9, 0.5);
  const RayBenchResult through_mesh = measure_ray_throughput(mesh, origin, 1080, seconds);
  const RayBenchResult through_boxes = measure_ray_throughput(boxes, origin, 1080, seconds);
  j["lidar_static_mesh"] = ratio_figure(through_mesh.scene_rays_per_s, "rays/s", through_boxes.scene_rays_per_s,
                                        "the same room (walls and 16 pillars) from box primitives, one thread");
  j["lidar_static_mesh"]["mesh_triangles"] = mesh.statics.back().geometry.mesh.triangles.size();
  j["lidar_static_mesh"]["bare_embree_mesh_rays_per_s"] = through_mesh.bare_rays_per_s;
  j["lidar_static_mesh"]["bare_embree_primitives_rays_per_s"] = through_boxes.bare_rays_per_s;
  return j;
}

}  // namespace rescuesim::bench
