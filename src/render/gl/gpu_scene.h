#pragma once
/// A RenderScene on the GPU: one vertex and index buffer for everything. Static items are baked
/// into world coordinates and drawn with one call (shadow casters first, so the floor can be left
/// out of the shadow pass); rubble and robot links keep their own frames and are drawn one call
/// each with a model matrix.

#include <vector>

#include <Eigen/Geometry>

#include "render/gl/gl_objects.h"
#include "render/render_scene.h"

namespace rescuesim::gl {

/// Which items a pass draws.
struct DrawFilter {
  RobotIndex hide_robot;       ///< robot whose links are skipped; invalid: none
  bool casters_only = false;   ///< only items that cast shadows
};

class GpuScene {
 public:
  /// Uploads meshes with per-vertex material index and apparent temperature
  /// (e·T + (1 − e)·T_ambient, K).
  void upload(const RenderScene& scene);
  /// New poses of the movable items (same scene layout as uploaded).
  void update(const RenderScene& scene);
  /// Draws with the bound program; `model_location` is its u_model uniform.
  void draw(GLuint program, GLint model_location, const DrawFilter& filter) const;
  /// World bounding box of everything that casts shadows (m).
  Eigen::AlignedBox3d caster_bounds() const;

 private:
  struct Range {
    GLsizei count = 0;           ///< indices
    std::size_t first = 0;       ///< first index
    GLint base_vertex = 0;
  };
  struct Movable {
    Range range;
    RobotIndex robot;
    bool casts_shadows = true;
    Eigen::Matrix4f model = Eigen::Matrix4f::Identity();  ///< item → world
    Eigen::AlignedBox3d local_bounds;                      ///< item frame (m)
    Eigen::AlignedBox3d world_bounds;
  };

  Buffer vertices_, indices_;
  VertexArray vao_;
  Range statics_all_, statics_casters_;
  Eigen::AlignedBox3d static_caster_bounds_;
  std::vector<Movable> movables_;
  std::vector<std::size_t> movable_items_;  ///< scene item index of each movable
};

}  // namespace rescuesim::gl
