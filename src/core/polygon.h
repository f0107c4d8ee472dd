#pragma once
/// Planar geometry on simple polygons (vertex lists, implicitly closed) in metres.

#include <array>
#include <vector>

#include "core/pose.h"

namespace rescuesim {

/// A simple polygon: vertices in order, the closing edge implied.
using Polygon2 = std::vector<Vec2>;

/// Axis-aligned box in the plane.
struct Box2 {
  Vec2 min{1e300, 1e300};
  Vec2 max{-1e300, -1e300};

  bool empty() const { return min.x() > max.x() || min.y() > max.y(); }
  void extend(const Vec2& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Box2& b) {
    if (b.empty()) return;
    extend(b.min);
    extend(b.max);
  }
  Vec2 size() const { return empty() ? Vec2::Zero() : Vec2(max - min); }
  bool contains(const Vec2& p) const { return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y(); }
  bool overlaps(const Box2& b) const {
    return !(b.min.x() > max.x() || b.max.x() < min.x() || b.min.y() > max.y() || b.max.y() < min.y());
  }
};

/// Signed area (m^2): positive for counter-clockwise vertex order.
double signed_area(const Polygon2& poly);
/// Area centroid; the vertex mean for degenerate polygons.
Vec2 centroid(const Polygon2& poly);
/// Bounding box.
Box2 bounds(const Polygon2& poly);
/// True when p is inside (even-odd rule; points on the boundary count as inside within eps).
bool contains(const Polygon2& poly, const Vec2& p, double eps = 1e-9);
/// Distance from p to segment [a, b].
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b);
/// Distance from p to the polygon: 0 inside, else to the nearest edge.
double distance_to_polygon(const Polygon2& poly, const Vec2& p);
/// True when the polygon has no two non-adjacent edges that cross.
bool is_simple(const Polygon2& poly);
/// Returns the polygon in counter-clockwise order with repeated and collinear vertices removed.
Polygon2 normalized(const Polygon2& poly, double eps = 1e-9);
/// Ear-clipping triangulation of a simple polygon: index triples into `poly`, counter-clockwise.
std::vector<std::array<int, 3>> triangulate(const Polygon2& poly);
/// Convex hull, counter-clockwise (Andrew's monotone chain).
Polygon2 convex_hull(std::vector<Vec2> points);
/// The polygon's principal axis angle (rad, in [0, pi)) and its extents along and across it,
/// from the minimum-area rectangle around the convex hull.
struct OrientedExtent {
  Vec2 center = Vec2::Zero();
  double angle = 0;   ///< direction of the long side
  double length = 0;  ///< long side (m)
  double width = 0;   ///< short side (m)
};
OrientedExtent oriented_extent(const Polygon2& poly);
/// Centre and extents of points measured along heading `yaw` and across it (m).
struct AxisExtent {
  Vec2 centre = Vec2::Zero();
  double along = 0, across = 0;
};
AxisExtent extent_along(const std::vector<Vec2>& points, double yaw);
/// Polygon of the rectangle of the given length and width around a pose.
Polygon2 rectangle(const Pose2& center, double length, double width);
/// True when the two simple polygons overlap (share interior or an edge crossing).
bool polygons_overlap(const Polygon2& a, const Polygon2& b);

}  // namespace rescuesim
