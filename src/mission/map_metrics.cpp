#include "mission/map_metrics.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "core/error.h"
#include "core/polygon.h"

namespace rescuesim::map_eval {

void Grid::cell_of(const Vec2& p, int& i, int& j) const {
  i = static_cast<int>(std::floor((p.x() - origin.x()) / resolution));
  j = static_cast<int>(std::floor((p.y() - origin.y()) / resolution));
}

namespace {

// an empty grid covering the world's floor with a cell of margin all round
Grid floor_grid(const WorldSpec& world, double resolution) {
  Grid g;
  g.resolution = resolution;
  g.origin = world.floor_min - Vec2(resolution, resolution);
  const Vec2 size = world.floor_max - world.floor_min;
  g.width = static_cast<int>(std::ceil(size.x() / resolution)) + 2;
  g.height = static_cast<int>(std::ceil(size.y() / resolution)) + 2;
  g.cells.assign(static_cast<std::size_t>(g.width) * g.height, 0);
  return g;
}

// marks the cells whose centre lies within `grow` of the polygon (inside it, or near an edge)
void mark_polygon(Grid& g, const Polygon2& poly, double grow) {
  const Box2 b = bounds(poly);
  int i0, j0, i1, j1;
  g.cell_of(b.min - Vec2(grow, grow), i0, j0);
  g.cell_of(b.max + Vec2(grow, grow), i1, j1);
  for (int j = std::max(j0, 0); j <= std::min(j1, g.height - 1); ++j)
    for (int i = std::max(i0, 0); i <= std::min(i1, g.width - 1); ++i)
      if (distance_to_polygon(poly, g.centre(i, j)) <= grow) g.at(i, j) = 1;
}

// the PGM's header fields and pixels (P5, maxval < 256)
std::vector<std::uint8_t> read_pgm(const std::filesystem::path& file, int& width, int& height) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("cannot read the map image " + file.string());
  std::string magic;
  in >> magic;
  if (magic != "P5") throw Error(file.string() + ": not a binary PGM (P5) image");
  int values[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    in >> std::ws;
    while (in.peek() == '#') {
      std::string comment;
      std::getline(in, comment);
      in >> std::ws;
    }
    if (!(in >> values[k])) throw Error(file.string() + ": bad PGM header");
  }
  width = values[0];
  height = values[1];
  if (width <= 0 || height <= 0 || values[2] <= 0 || values[2] > 255)
    throw Error(file.string() + ": PGM size or maximum value out of range (8-bit images only)");
  in.get();  // the single whitespace after the header
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * height);
  if (!in.read(reinterpret_cast<char*>(px.data()), static_cast<std::streamsize>(px.size())))
    throw Error(file.string() + ": truncated PGM (expected " + std::to_string(px.size()) + " pixels)");
  return px;
}

}  // namespace

SlamMap read_map(const std::filesystem::path& yaml) {
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(yaml.string());
  } catch (const std::exception& e) {
    throw Error("cannot read the map " + yaml.string() + ": " + e.what());
  }
  auto need = [&](const char* key) {
    if (!doc[key]) throw Error(yaml.string() + ": missing key '" + key + "' (map_server format)");
    return doc[key];
  };
  SlamMap m;
  m.yaml = yaml;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  int negate = 0;
  std::filesystem::path image;
  std::vector<double> origin;
  try {
    image = need("image").as<std::string>();
    m.grid.resolution = need("resolution").as<double>();
    origin = need("origin").as<std::vector<double>>();
    if (doc["occupied_thresh"]) occupied_thresh = doc["occupied_thresh"].as<double>();
    if (doc["free_thresh"]) free_thresh = doc["free_thresh"].as<double>();
    if (doc["negate"]) negate = doc["negate"].as<int>();
  } catch (const YAML::Exception& e) {
    throw Error(yaml.string() + ": " + e.what());
  }
  if (!(m.grid.resolution > 0)) throw Error(yaml.string() + ": resolution must be > 0");
  if (origin.size() != 3) throw Error(yaml.string() + ": origin must be [x, y, yaw]");
  if (std::fabs(origin[2]) > 1e-9) throw Error(yaml.string() + ": a rotated map origin is not supported");
  m.grid.origin = Vec2(origin[0], origin[1]);
  if (image.is_relative()) image = yaml.parent_path() / image;
  const auto px = read_pgm(image, m.grid.width, m.grid.height);
  m.grid.cells.resize(px.size());
  // the image's first row is the northern edge of the map
  for (int j = 0; j < m.grid.height; ++j)
    for (int i = 0; i < m.grid.width; ++i) {
      const double v = px[static_cast<std::size_t>(m.grid.height - 1 - j) * m.grid.width + i] / 255.0;
      const double occ = negate ? v : 1.0 - v;
      m.grid.at(i, j) = occ > occupied_thresh ? kOccupied : occ < free_thresh ? kFree : kUnknown;
    }
  return m;
}

Grid true_occupancy(const WorldSpec& world, double resolution, double laser_height) {
  Grid g = floor_grid(world, resolution);
  const double grow = resolution / 2;
  for (const auto& w : world.walls)
    if (w.height > laser_height) mark_polygon(g, WorldSpec::wall_outline(w), grow);
  for (const auto& b : world.blocks)
    if (b.height > laser_height) mark_polygon(g, b.outline, grow);
  return g;
}

Grid ignore_mask(const WorldSpec& world, const Grid& like, double margin) {
  Grid g = like;
  std::fill(g.cells.begin(), g.cells.end(), 0);
  for (const auto& v : world.victims) mark_polygon(g, WorldSpec::victim_outline(v), margin);
  return g;
}

void add_visible(Grid& seen, const Grid& truth, const Pose2& X_WB, const LaserModel& laser) {
  const double res = truth.resolution;
  const Pose2 X_WL = X_WB * laser.X_BL;
  // walk each beam through the grid cell by cell (Amanatides & Woo) to the first occupied one
  for (int k = 0; k < laser.beams; ++k) {
    const double a = X_WL.yaw + laser.min_angle + (laser.beams > 1 ? k * (laser.max_angle - laser.min_angle) / (laser.beams - 1) : 0.0);
    const double dx = std::cos(a), dy = std::sin(a);
    int i, j;
    truth.cell_of(X_WL.position(), i, j);
    const int si = dx > 0 ? 1 : -1, sj = dy > 0 ? 1 : -1;
    const Vec2 p = (X_WL.position() - truth.origin) / res;  // in cells
    double t_max_x =
        std::fabs(dx) < 1e-12 ? INFINITY : ((si > 0 ? std::floor(p.x()) + 1 - p.x() : p.x() - std::floor(p.x())) / std::fabs(dx));
    double t_max_y =
        std::fabs(dy) < 1e-12 ? INFINITY : ((sj > 0 ? std::floor(p.y()) + 1 - p.y() : p.y() - std::floor(p.y())) / std::fabs(dy));
    const double t_dx = std::fabs(dx) < 1e-12 ? INFINITY : 1 / std::fabs(dx);
    const double t_dy = std::fabs(dy) < 1e-12 ? INFINITY : 1 / std::fabs(dy);
    const double t_end = laser.max_range / res;
    double t = 0;
    while (t <= t_end && truth.inside(i, j)) {
      if (truth.at(i, j)) {
        seen.at(i, j) = 1;
        break;
      }
      if (t_max_x < t_max_y) {
        t = t_max_x;
        t_max_x += t_dx;
        i += si;
      } else {
        t = t_max_y;
        t_max_y += t_dy;
        j += sj;
      }
    }
  }
}

Grid visible_surface(const Grid& truth, const std::vector<Pose2>& poses, const LaserModel& laser) {
  Grid seen = truth;
  std::fill(seen.cells.begin(), seen.cells.end(), 0);
  for (const Pose2& X_WB : poses) add_visible(seen, truth, X_WB, laser);
  return seen;
}

Grid grid_from_occupancy(int width, int height, double resolution, const std::vector<std::int8_t>& data,
                         int free_max, int occupied_min) {
  if (!(resolution > 0) || !std::isfinite(resolution)) {
    throw Error("map: resolution " + std::to_string(resolution) + " m is not a positive number");
  }
  if (width < 0 || height < 0 || static_cast<std::size_t>(width) * static_cast<std::size_t>(height) != data.size()) {
    throw Error("map: " + std::to_string(data.size()) + " cells of data for " + std::to_string(width) + " x " + std::to_string(height));
  }
  Grid g;
  g.resolution = resolution;
  g.width = width;
  g.height = height;
  g.cells.resize(data.size());
  for (std::size_t k = 0; k < data.size(); ++k) {
    const int v = data[k];
    g.cells[k] = v < 0 ? kUnknown : v <= free_max ? kFree : v >= occupied_min ? kOccupied : kUnknown;
  }
  return g;
}

MapScore score_map(const SlamMap& map, const Pose2& X_WM, const Grid& truth, const Grid& visible, const Grid& ignore, int tol) {
  return score_map(map.grid, X_WM, truth, visible, ignore, tol);
}

MapScore score_map(const Grid& m, const Pose2& X_WM, const Grid& truth, const Grid& visible, const Grid& ignore, int tol) {
  MapScore s;
  auto any_near = [tol](const Grid& g, int i, int j, auto&& pred) {
    for (int dj = -tol; dj <= tol; ++dj)
      for (int di = -tol; di <= tol; ++di)
        if (g.inside(i + di, j + dj) && pred(g.at(i + di, j + dj))) return true;
    return false;
  };
  // precision: each occupied map cell, placed in the world, should lie on a true obstacle
  for (int j = 0; j < m.height; ++j)
    for (int i = 0; i < m.width; ++i) {
      if (m.at(i, j) != kOccupied) continue;
      int ti, tj;
      truth.cell_of(X_WM.transform(m.centre(i, j)), ti, tj);
      if (ignore.inside(ti, tj) && ignore.at(ti, tj)) {
        ++s.map_ignored;
        continue;
      }
      ++s.map_occupied;
      if (any_near(truth, ti, tj, [](std::uint8_t v) { return v != 0; })) ++s.map_matched;
    }
  // recall: each obstacle cell the laser could have seen should be occupied in the map
  const Pose2 X_MW = X_WM.inverse();
  for (int j = 0; j < visible.height; ++j)
    for (int i = 0; i < visible.width; ++i) {
      if (!visible.at(i, j)) continue;
      ++s.visible;
      int mi, mj;
      m.cell_of(X_MW.transform(visible.centre(i, j)), mi, mj);
      if (any_near(m, mi, mj, [](std::uint8_t v) { return v == kOccupied; })) ++s.visible_matched;
    }
  s.precision = s.map_occupied ? double(s.map_matched) / double(s.map_occupied) : 0.0;
  s.recall = s.visible ? double(s.visible_matched) / double(s.visible) : 0.0;
  return s;
}

TrajectoryError trajectory_error(const std::vector<Pose2>& truth, const std::vector<Pose2>& estimate, Alignment alignment) {
  TrajectoryError e;
  e.pairs = std::min(truth.size(), estimate.size());
  if (e.pairs == 0) return e;
  if (alignment == Alignment::start) {
    e.X_WM = truth[0] * estimate[0].inverse();
  } else {
    // Umeyama in 2-D without scale: the rotation from the centred cross-covariance
    Vec2 ct = Vec2::Zero(), ce = Vec2::Zero();
    for (std::size_t k = 0; k < e.pairs; ++k) {
      ct += truth[k].position();
      ce += estimate[k].position();
    }
    ct /= double(e.pairs);
    ce /= double(e.pairs);
    double sin_sum = 0, cos_sum = 0;
    for (std::size_t k = 0; k < e.pairs; ++k) {
      const Vec2 a = estimate[k].position() - ce, b = truth[k].position() - ct;
      cos_sum += a.x() * b.x() + a.y() * b.y();
      sin_sum += a.x() * b.y() - a.y() * b.x();
    }
    const double yaw = std::atan2(sin_sum, cos_sum);
    const Pose2 R{0, 0, yaw};
    const Vec2 t = ct - R.transform(ce);
    e.X_WM = {t.x(), t.y(), yaw};
  }
  double sum = 0;
  for (std::size_t k = 0; k < e.pairs; ++k) {
    const double d = (e.X_WM.transform(estimate[k].position()) - truth[k].position()).norm();
    sum += d * d;
    e.max = std::max(e.max, d);
  }
  e.rmse = std::sqrt(sum / double(e.pairs));
  return e;
}

}  // namespace rescuesim::map_eval
