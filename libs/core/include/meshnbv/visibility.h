// Visibility of vertices and faces in views (SPEC section 2), by ray
// casting with Embree. Vertex visibility is computed once per
// (vertex, view) and shared by all faces: O(V x views) rays.
#pragma once

#include <cstdint>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/mesh.h"
#include "meshnbv/progress.h"
#include "meshnbv/raycaster.h"

namespace meshnbv {

struct VisibilityOptions {
  double relative_eps = 1e-4;           // the segment stops at (1 - eps) |v - C| ...
  double absolute_eps_of_diagonal = 1e-6;  // ... minus this share of the bbox diagonal

  void check() const;  // throws Error for values out of range: both in [0, 1)
};

class VertexVisibility {
 public:
  VertexVisibility() = default;
  // Vertex v is visible in camera i when it is in front (z > 0), projects
  // inside [0, W-1] x [0, H-1], and nothing hits the segment from the
  // centre before (1 - eps) |v - C| - bias. Runs in parallel over vertices.
  VertexVisibility(const TriangleMesh& mesh, const RayCaster& caster,
                   const std::vector<PinholeCamera>& cameras, const VisibilityOptions& options = {},
                   const ProgressCallback& progress = {});
  // The same for the vertices listed in `vertices` only (a tile of the
  // mesh, docs/scale.md): the rays are those of the whole-mesh constructor,
  // against the whole mesh, so each listed vertex gets the same answer;
  // visible() of an unlisted vertex is false. Memory: one row per listed vertex.
  VertexVisibility(const TriangleMesh& mesh, const RayCaster& caster,
                   const std::vector<PinholeCamera>& cameras, const VisibilityOptions& options,
                   const ProgressCallback& progress, const std::vector<std::uint32_t>& vertices);

  bool visible(std::size_t vertex, std::size_t view) const {
    if (row_.empty()) return bits_[vertex * num_views_ + view] != 0;
    const std::uint32_t r = row_[vertex];
    return r != kNoRow && bits_[std::size_t(r) * num_views_ + view] != 0;
  }
  std::size_t num_views() const { return num_views_; }

 private:
  static constexpr std::uint32_t kNoRow = 0xffffffffu;
  void compute(const TriangleMesh& mesh, const RayCaster& caster,
               const std::vector<PinholeCamera>& cameras, const VisibilityOptions& options,
               const ProgressCallback& progress, const std::vector<std::uint32_t>* vertices);
  std::size_t num_views_ = 0;
  std::vector<std::uint8_t> bits_;  // row-major: one row of num_views_ per vertex
  std::vector<std::uint32_t> row_;  // subset: row of each vertex (kNoRow when unlisted); empty = every vertex, row = vertex
};

// Face f is visible in view i when its three vertices are visible and it
// faces the camera: dot(n_f, C_i - centroid_f) > 0 (the back-face rule).
bool face_visible(const TriangleMesh& mesh, const std::vector<Vec3>& face_normals,
                  const VertexVisibility& visibility, std::size_t face, std::size_t view,
                  const Vec3& camera_center);

// Visibility of a single point from a camera under the same rules.
bool point_visible(const RayCaster& caster, const PinholeCamera& camera, const Vec3& point,
                   double relative_eps, double absolute_eps);

}  // namespace meshnbv
