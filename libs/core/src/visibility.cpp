#include "meshnbv/visibility.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "meshnbv/error.h"

namespace meshnbv {

void VisibilityOptions::check() const {
  check_option(relative_eps >= 0 && relative_eps < 1, "visibility relative_eps", "in [0, 1)",
               relative_eps);
  check_option(absolute_eps_of_diagonal >= 0 && absolute_eps_of_diagonal < 1,
               "visibility absolute_eps_of_diagonal", "in [0, 1)", absolute_eps_of_diagonal);
}

bool point_visible(const RayCaster& caster, const PinholeCamera& camera, const Vec3& point,
                   double relative_eps, double absolute_eps) {
  Vec2 px;
  if (!camera.project(point, &px) || !camera.in_image(px)) return false;
  return caster.segment_clear(camera.center(), point, relative_eps, absolute_eps);
}

VertexVisibility::VertexVisibility(const TriangleMesh& mesh, const RayCaster& caster,
                                   const std::vector<PinholeCamera>& cameras,
                                   const VisibilityOptions& options,
                                   const ProgressCallback& progress) {
  compute(mesh, caster, cameras, options, progress, nullptr);
}

VertexVisibility::VertexVisibility(const TriangleMesh& mesh, const RayCaster& caster,
                                   const std::vector<PinholeCamera>& cameras,
                                   const VisibilityOptions& options,
                                   const ProgressCallback& progress,
                                   const std::vector<std::uint32_t>& vertices) {
  row_.assign(mesh.num_vertices(), kNoRow);
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    if (vertices[k] >= mesh.num_vertices())
      throw Error("vertex " + std::to_string(vertices[k]) + " of a visibility subset is out of range");
    row_[vertices[k]] = std::uint32_t(k);
  }
  compute(mesh, caster, cameras, options, progress, &vertices);
}

void VertexVisibility::compute(const TriangleMesh& mesh, const RayCaster& caster,
                               const std::vector<PinholeCamera>& cameras,
                               const VisibilityOptions& options, const ProgressCallback& progress,
                               const std::vector<std::uint32_t>* vertices) {
  num_views_ = cameras.size();
  const double abs_eps = options.absolute_eps_of_diagonal * mesh.bounding_box().diagonal();
  const std::size_t V = vertices ? vertices->size() : mesh.num_vertices();
  bits_.assign(V * num_views_, 0);
  // Chunks of vertices in parallel; progress and cancellation between chunks.
  const std::size_t chunk = 16384;
  for (std::size_t begin = 0; begin < V; begin += chunk) {
    const std::size_t end = std::min(V, begin + chunk);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        // View by view: consecutive rays share an origin and
                        // walk nearby parts of the BVH.
                        for (std::size_t i = 0; i < num_views_; ++i)
                          for (std::size_t k = r.begin(); k < r.end(); ++k) {
                            const std::size_t v = vertices ? (*vertices)[k] : k;
                            bits_[k * num_views_ + i] = point_visible(
                                caster, cameras[i], mesh.vertices[v], options.relative_eps, abs_eps);
                          }
                      });
    report_progress(progress, double(end) / double(V), "visibility");
  }
}

bool face_visible(const TriangleMesh& mesh, const std::vector<Vec3>& face_normals,
                  const VertexVisibility& visibility, std::size_t face, std::size_t view,
                  const Vec3& camera_center) {
  const Face& f = mesh.faces[face];
  for (int k = 0; k < 3; ++k)
    if (!visibility.visible(std::size_t(f[k]), view)) return false;
  return face_normals[face].dot(camera_center - mesh.face_centroid(face)) > 0;
}

}  // namespace meshnbv
