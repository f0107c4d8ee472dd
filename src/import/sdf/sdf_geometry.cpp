// SDF shapes, inertials and materials: an sdf::Geometry becomes rescuesim Geometry (meshes
// through import/mesh), a link's <inertial> (or a density estimate) its mass properties, and a
// link's visual its material.
#include <cmath>

#include "import/sdf/sdf_detail.h"

namespace rescuesim::sdf_detail {

namespace {

namespace fs = std::filesystem;

/// Collision meshes of robot links: decompose when the hull is this much bigger than the mesh
/// (UrdfOptions::decompose_ratio's default; SdfOptions has no field of its own for it).
constexpr double kDecomposeRatio = 1.5;

std::string num(double v) { return std::to_string(v); }

/// Throws unless `v` is a positive, finite size no larger than max_extent.
void check_size(double v, const std::string& what, const SourceRef& where, const SdfOptions& options) {
  if (!std::isfinite(v) || !(v > 0)) throw Error(where, what + " must be positive and finite, got " + num(v));
  if (v > options.max_extent) {
    throw Error(where,
                what + " is " + num(v) + " m, beyond the largest sane extent (" + num(options.max_extent) + " m, SdfOptions::max_extent)");
  }
}

/// A convex solid round a set of points (capsules and ellipsoids, which Geometry has not).
Geometry convex_of(const std::vector<Vec3>& points) { return Geometry::convex(convex_hull(points, 512)); }

/// Points on the unit sphere in latitude rings that include both poles and the equator (so a
/// hull of them reaches the shape's full extent along every axis).
std::vector<Vec3> unit_sphere_points() {
  constexpr int kRings = 8, kAround = 24;  // rings per hemisphere, points per ring
  std::vector<Vec3> out{Vec3::UnitZ(), -Vec3::UnitZ()};
  for (int i = -kRings + 1; i < kRings; ++i) {
    const double lat = 0.5 * M_PI * i / kRings;
    for (int k = 0; k < kAround; ++k) {
      const double lon = 2 * M_PI * k / kAround;
      out.emplace_back(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
    }
  }
  return out;
}

Geometry capsule(double radius, double length) {
  // the sphere's upper half raised and its lower half lowered by half the length (the equator
  // ring goes to both)
  std::vector<Vec3> points;
  for (const Vec3& u : unit_sphere_points()) {
    for (double side : {1.0, -1.0}) {
      if (u.z() * side >= 0) points.push_back(radius * u + Vec3(0, 0, side * 0.5 * length));
    }
  }
  return convex_of(points);
}

Geometry ellipsoid(const Vec3& radii) {
  std::vector<Vec3> points = unit_sphere_points();
  for (Vec3& p : points) p = p.cwiseProduct(radii);
  return convex_of(points);
}

/// A plane: the floor when it is z = 0 facing up; else a slab 1 cm thick under its face.
Shape plane(const sdf::Plane& pl, const Pose3& X_WG, const SourceRef& where, const SdfOptions& options) {
  Shape out;
  const Vec3 n = vec_of(pl.Normal()).normalized();
  const Vec3 n_W = X_WG.q * n;
  if (n_W.z() > 1 - 1e-9 && std::abs(X_WG.p.z()) < 1e-9) {
    out.floor = true;
    return out;
  }
  check_size(pl.Size().X(), "plane size x", where, options);
  check_size(pl.Size().Y(), "plane size y", where, options);
  constexpr double kThickness = 0.01;
  const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), n);
  out.pieces.push_back({Geometry::box({pl.Size().X(), pl.Size().Y(), kThickness}), Pose3{-0.5 * kThickness * n, q}});
  return out;
}

/// The convex pieces of a collision mesh on a moving link, as the URDF importer makes them.
std::vector<TriangleMesh> convex_pieces(const TriangleMesh& mesh, const SdfOptions& options) {
  TriangleMesh hull = convex_hull(mesh.vertices, options.hull_vertices);
  const double mesh_volume = mass_properties(mesh).volume, hull_volume = mass_properties(hull).volume;
  const bool decompose = options.collision == CollisionMode::decompose ||
                         (options.collision == CollisionMode::automatic && mesh_volume > 0 && hull_volume > kDecomposeRatio * mesh_volume);
  if (!decompose) return {std::move(hull)};
  DecompositionOptions d;
  d.max_vertices_per_hull = std::min(options.hull_vertices, 32);
  return convex_decomposition(mesh, d);
}

Shape mesh(const sdf::Mesh& m, MeshUse use, const ShapeOwner& owner, Reader& r) {
  const SourceRef where = r.at(m.Element(), owner.element);
  const SdfOptions& options = r.options;
  if (!m.Submesh().empty()) {
    r.diagnostics.warn(where, "<submesh> '" + m.Submesh() + "' is ignored: the whole mesh file is used");
  }
  const Vec3 scale = vec_of(m.Scale());
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(scale[i]) || scale[i] == 0 || std::abs(scale[i]) > options.max_extent) {
      throw Error(where, "<scale> " + num(scale.x()) + " " + num(scale.y()) + " " + num(scale.z()) +
                             " is absurd: each factor must be finite, non-zero and at most " + num(options.max_extent));
    }
  }
  // the mesh element's own file anchors relative URIs (an included model's model.sdf)
  SourceRef anchor = where;
  anchor.element += " <uri>" + m.Uri() + "</uri>";
  const fs::path file = options.resolver.resolve(m.Uri(), anchor);
  const auto key = std::make_tuple(file.string(), scale.x(), scale.y(), scale.z());
  auto it = r.cache.find(key);
  if (it == r.cache.end()) {
    MeshLoadOptions o;
    o.scale = scale;
    o.max_triangles = options.max_triangles;
    it = r.cache.emplace(key, load_mesh(file, o, anchor)).first;
  }
  const LoadedMesh& loaded = it->second;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& v : loaded.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  if ((hi - lo).maxCoeff() > options.max_extent || !lo.allFinite() || !hi.allFinite()) {
    throw Error(anchor, "mesh " + file.string() + " spans " + num((hi - lo).maxCoeff()) +
                            " m after scaling, beyond the largest sane extent (" + num(options.max_extent) + " m)");
  }

  // a texture is drawn on an exact mesh (a static model's); convex pieces have no texture coordinates
  SdfMeshReport report{owner.model, owner.link, m.Uri(), file.string(), owner.collision, use == MeshUse::exact,
                       static_cast<int>(loaded.mesh.triangles.size()), loaded.texture, loaded.image && use == MeshUse::exact};
  r.meshes.push_back(report);
  Shape out;
  out.mesh_color = loaded.color;
  if (use == MeshUse::exact) {
    Geometry g = Geometry::triangles(loaded.mesh);
    g.image = loaded.image;
    out.pieces.push_back({std::move(g), Pose3{}});
    return out;
  }
  try {
    for (auto& p : convex_pieces(loaded.mesh, options)) out.pieces.push_back({Geometry::convex(std::move(p)), Pose3{}});
  } catch (const Error& e) {
    throw Error(anchor, "collision mesh " + file.string() + ": " + e.message());
  }
  return out;
}

/// Volume, centroid and unit-density inertia of one shape in its own frame: exact for boxes,
/// cylinders and spheres, from the triangles otherwise.
MassProperties unit_mass_properties(const Geometry& g) {
  MassProperties mp;
  const Vec3 s = g.size;
  switch (g.type) {
    case Geometry::Type::box:
      mp.volume = s.x() * s.y() * s.z();
      mp.inertia = (mp.volume / 12.0 * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y()))
                       .asDiagonal();
      return mp;
    case Geometry::Type::cylinder: {
      const double rr = 0.25 * s.x() * s.x(), h = s.z();
      mp.volume = M_PI * rr * h;
      mp.inertia = (mp.volume * Vec3((3 * rr + h * h) / 12.0, (3 * rr + h * h) / 12.0, rr / 2.0)).asDiagonal();
      return mp;
    }
    case Geometry::Type::sphere: {
      const double rr = 0.25 * s.x() * s.x();
      mp.volume = 4.0 / 3.0 * M_PI * rr * std::sqrt(rr);
      mp.inertia = (mp.volume * 0.4 * rr * Vec3::Ones()).asDiagonal();
      return mp;
    }
    default: return mass_properties(g.type == Geometry::Type::mesh || g.type == Geometry::Type::convex ? g.mesh : mesh_of(g, 32));
  }
}

}  // namespace

Shape shape_of(const sdf::Geometry& g, const Pose3& X_WG, MeshUse use, const ShapeOwner& owner, Reader& r) {
  const SourceRef where = r.at(g.Element(), owner.element);
  const SdfOptions& o = r.options;
  Shape out;
  auto one = [&out](Geometry geometry) {
    out.pieces.push_back({std::move(geometry), Pose3{}});
    return out;
  };
  switch (g.Type()) {
    case sdf::GeometryType::BOX: {
      const Vec3 size = vec_of(g.BoxShape()->Size());
      for (int i = 0; i < 3; ++i) check_size(size[i], std::string("<box><size> ") + "xyz"[i], where, o);
      return one(Geometry::box(size));
    }
    case sdf::GeometryType::CYLINDER:
      check_size(g.CylinderShape()->Radius(), "<cylinder><radius>", where, o);
      check_size(g.CylinderShape()->Length(), "<cylinder><length>", where, o);
      return one(Geometry::cylinder(g.CylinderShape()->Radius(), g.CylinderShape()->Length()));
    case sdf::GeometryType::SPHERE:
      check_size(g.SphereShape()->Radius(), "<sphere><radius>", where, o);
      return one(Geometry::sphere(g.SphereShape()->Radius()));
    case sdf::GeometryType::CAPSULE:
      check_size(g.CapsuleShape()->Radius(), "<capsule><radius>", where, o);
      check_size(g.CapsuleShape()->Length(), "<capsule><length>", where, o);
      return one(capsule(g.CapsuleShape()->Radius(), g.CapsuleShape()->Length()));
    case sdf::GeometryType::ELLIPSOID: {
      const Vec3 radii = vec_of(g.EllipsoidShape()->Radii());
      for (int i = 0; i < 3; ++i) check_size(radii[i], std::string("<ellipsoid><radii> ") + "xyz"[i], where, o);
      return one(ellipsoid(radii));
    }
    case sdf::GeometryType::PLANE: return plane(*g.PlaneShape(), X_WG, where, o);
    case sdf::GeometryType::MESH: return mesh(*g.MeshShape(), use, owner, r);
    case sdf::GeometryType::HEIGHTMAP:
      r.diagnostics.warn(where, "<heightmap> is not supported yet: this shape is left out");
      return out;
    default:
      r.diagnostics.warn(where, "a geometry of this type is not supported: this shape is left out");
      return out;
  }
}

Inertial inertial_of(const sdf::Link& link, const std::vector<Piece>& shapes_L, const std::string& model, Reader& r) {
  Inertial in;
  const SourceRef where = r.at(link.Element(), "<model name=\"" + model + "\">");
  if (link.Element()->HasElement("inertial")) {
    const auto& mm = link.Inertial().MassMatrix();
    in.mass = mm.Mass();
    in.X_LI = pose_of(link.Inertial().Pose());
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) in.I(i, j) = mm.Moi()(i, j);
    }
    if (!std::isfinite(in.mass) || !(in.mass > 0) || !in.I.allFinite()) {
      throw Error(where, "link '" + link.Name() + "': <inertial> needs a positive <mass> and finite <inertia>, got mass " + num(in.mass));
    }
    return in;
  }
  if (shapes_L.empty()) return in;
  const double density = r.options.default_density;
  if (shapes_L.size() == 1) {
    const MassProperties mp = unit_mass_properties(shapes_L.front().geometry);
    in.X_LI = shapes_L.front().X_GP * Pose3{mp.centroid, Quat::Identity()};
    in.mass = density * mp.volume;
    in.I = density * mp.inertia;
  } else {
    // several shapes: the solid of their convex hull
    std::vector<Vec3> points;
    for (const Piece& p : shapes_L) {
      for (const Vec3& v : mesh_of(p.geometry, 24).vertices) points.push_back(p.X_GP * v);
    }
    const MassProperties mp = mass_properties(convex_hull(points, 256));
    in.X_LI = Pose3{mp.centroid, Quat::Identity()};
    in.mass = density * mp.volume;
    in.I = density * mp.inertia;
  }
  r.diagnostics.warn(where, "link '" + link.Name() + "' has no <inertial>: assuming " + num(in.mass) + " kg (" + num(density) +
                                " kg/m^3 over its collision shapes); give an <inertial> for faithful dynamics");
  return in;
}

std::optional<Vec3> visual_color(const sdf::Visual& visual) {
  const sdf::Material* m = visual.Material();
  if (!m || !m->Element()) return std::nullopt;
  if (m->Element()->HasElement("diffuse")) return color_of(m->Diffuse());
  if (m->Element()->HasElement("ambient")) return color_of(m->Ambient());
  return std::nullopt;
}

std::optional<double> friction_of(const sdf::Collision& c) {
  sdf::ElementPtr e = c.Element();
  for (const char* name : {"surface", "friction", "ode", "mu"}) {
    if (!e || !e->HasElement(name)) return std::nullopt;
    e = e->GetElement(name);
  }
  return e->Get<double>();
}

std::string material_of(const sdf::Link& link, const sdf::Collision* collision, const std::string& model,
                        const std::optional<Vec3>& mesh_color, const MaterialSpec& fallback, std::vector<MaterialSpec>& materials) {
  const sdf::Visual* visual = link.VisualCount() > 0 ? link.VisualByIndex(0) : nullptr;
  std::optional<Vec3> color = visual ? visual_color(*visual) : std::nullopt;
  if (!color) color = mesh_color;
  const std::optional<double> mu = collision ? friction_of(*collision) : std::nullopt;
  if (!color && !mu) return fallback.name;
  MaterialSpec m = fallback;
  m.name = model + "::" + link.Name() + "::" + (visual ? visual->Name() : "mesh");
  if (color) m.color = color->cwiseMax(0.0).cwiseMin(1.0);
  if (mu) {
    m.friction = std::clamp(*mu, 0.0, 1000.0);
    m.name = model + "::" + link.Name() + "::" + collision->Name();
  }
  const auto it = std::find_if(materials.begin(), materials.end(), [&](const MaterialSpec& x) { return x.name == m.name; });
  if (it == materials.end()) {
    materials.push_back(m);
  } else {
    *it = m;
  }
  return m.name;
}

}  // namespace rescuesim::sdf_detail
