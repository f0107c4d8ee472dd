#include "render/gl/gpu_scene.h"

#include <algorithm>
#include <cstddef>

namespace rescuesim::gl {

namespace {

/// The interleaved vertex of every pass.
struct Vertex {
  float position[3];
  float normal[3];
  float uv[2];
  float material;
  float temperature;  ///< apparent (K)
};

Eigen::AlignedBox3d transformed(const Eigen::AlignedBox3d& box, const Eigen::Matrix4f& X) {
  Eigen::AlignedBox3d out;
  if (box.isEmpty()) return out;
  for (int c = 0; c < 8; ++c) {
    out.extend((X * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).cast<float>().homogeneous()).head<3>().cast<double>());
  }
  return out;
}

Eigen::Matrix4f pose_matrix(const Pose3& X) { return X.isometry().matrix().cast<float>(); }

}  // namespace

void GpuScene::upload(const RenderScene& scene) {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  const auto apparent = [&](const RenderItem& item) {
    const double e = scene.materials[static_cast<std::size_t>(item.material)].emissivity;
    return static_cast<float>(e * item.temperature + (1 - e) * scene.ambient_temperature);
  };
  // append one item's mesh; statics are baked into world coordinates, movables stay in their frame
  const auto append = [&](const RenderItem& item, bool bake, bool rebase) {
    const RenderMesh& mesh = scene.meshes[static_cast<std::size_t>(item.mesh)];
    const Eigen::Matrix3d R = item.X_WI.q.toRotationMatrix();
    const std::size_t first_vertex = vertices.size();
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      Vertex v;
      Eigen::Vector3f p = mesh.positions[i], n = mesh.normals[i];
      if (bake) {
        p = (item.X_WI * mesh.positions[i].cast<double>()).cast<float>();
        n = (R * mesh.normals[i].cast<double>()).cast<float>();
      }
      std::copy_n(p.data(), 3, v.position);
      std::copy_n(n.data(), 3, v.normal);
      v.uv[0] = mesh.uvs[i].x();
      v.uv[1] = mesh.uvs[i].y();
      v.material = static_cast<float>(item.material);
      v.temperature = apparent(item);
      vertices.push_back(v);
    }
    const auto offset = static_cast<std::uint32_t>(rebase ? first_vertex : 0);
    for (std::uint32_t k : mesh.indices) indices.push_back(k + offset);
  };

  // statics: shadow casters first, then the rest (the floor)
  statics_casters_ = {};
  for (int pass = 0; pass < 2; ++pass) {
    for (const RenderItem& item : scene.items) {
      if (item.movable() || item.casts_shadows != (pass == 0)) continue;
      append(item, true, true);
    }
    if (pass == 0) statics_casters_.count = static_cast<GLsizei>(indices.size());
  }
  statics_all_ = {static_cast<GLsizei>(indices.size()), 0, 0};
  static_caster_bounds_.setEmpty();
  for (GLsizei i = 0; i < statics_casters_.count; ++i) {
    const float* p = vertices[indices[static_cast<std::size_t>(i)]].position;
    static_caster_bounds_.extend(Eigen::Vector3d(p[0], p[1], p[2]));
  }

  // movables: their own ranges, drawn with a model matrix
  movables_.clear();
  movable_items_.clear();
  for (std::size_t k = 0; k < scene.items.size(); ++k) {
    const RenderItem& item = scene.items[k];
    if (!item.movable()) continue;
    Movable m;
    m.range = {0, indices.size(), static_cast<GLint>(vertices.size())};
    append(item, false, false);
    m.range.count = static_cast<GLsizei>(indices.size() - m.range.first);
    m.robot = item.robot;
    m.casts_shadows = item.casts_shadows;
    for (const auto& p : scene.meshes[static_cast<std::size_t>(item.mesh)].positions) m.local_bounds.extend(p.cast<double>());
    movables_.push_back(m);
    movable_items_.push_back(k);
  }

  vertices_ = Buffer(vertices.size() * sizeof(Vertex), vertices.data());
  indices_ = Buffer(indices.size() * sizeof(std::uint32_t), indices.data());
  vao_ = VertexArray::create();
  glVertexArrayVertexBuffer(vao_.id(), 0, vertices_.id(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao_.id(), indices_.id());
  const auto attribute = [&](GLuint location, GLint size, std::size_t offset) {
    glEnableVertexArrayAttrib(vao_.id(), location);
    glVertexArrayAttribFormat(vao_.id(), location, size, GL_FLOAT, GL_FALSE, static_cast<GLuint>(offset));
    glVertexArrayAttribBinding(vao_.id(), location, 0);
  };
  attribute(0, 3, offsetof(Vertex, position));
  attribute(1, 3, offsetof(Vertex, normal));
  attribute(2, 2, offsetof(Vertex, uv));
  attribute(3, 1, offsetof(Vertex, material));
  attribute(4, 1, offsetof(Vertex, temperature));
  update(scene);
}

void GpuScene::update(const RenderScene& scene) {
  for (std::size_t i = 0; i < movables_.size(); ++i) {
    Movable& m = movables_[i];
    m.model = pose_matrix(scene.items[movable_items_[i]].X_WI);
    m.world_bounds = transformed(m.local_bounds, m.model);
  }
}

void GpuScene::draw(GLuint program, GLint model_location, const DrawFilter& filter) const {
  glBindVertexArray(vao_.id());
  const Eigen::Matrix4f identity = Eigen::Matrix4f::Identity();
  glProgramUniformMatrix4fv(program, model_location, 1, GL_FALSE, identity.data());
  const Range& statics = filter.casters_only ? statics_casters_ : statics_all_;
  if (statics.count > 0) glDrawElements(GL_TRIANGLES, statics.count, GL_UNSIGNED_INT, nullptr);
  for (const Movable& m : movables_) {
    if ((filter.casters_only && !m.casts_shadows) || (m.robot.valid() && m.robot == filter.hide_robot) || m.range.count == 0) continue;
    glProgramUniformMatrix4fv(program, model_location, 1, GL_FALSE, m.model.data());
    glDrawElementsBaseVertex(GL_TRIANGLES, m.range.count, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(m.range.first * sizeof(std::uint32_t)), m.range.base_vertex);
  }
}

Eigen::AlignedBox3d GpuScene::caster_bounds() const {
  Eigen::AlignedBox3d box = static_caster_bounds_;
  for (const Movable& m : movables_) {
    if (m.casts_shadows) box.extend(m.world_bounds);
  }
  return box;
}

}  // namespace rescuesim::gl
