// Distances from points to a triangle surface (CGAL AABB tree). Queries
// are const and thread-safe once built.
#pragma once

#include <memory>

#include "meshnbv/mesh.h"

namespace meshnbv {

class SurfaceDistance {
 public:
  // Throws Error when the mesh is invalid or has no non-degenerate face.
  explicit SurfaceDistance(const TriangleMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;

  double distance(const Vec3& p) const;
  Vec3 closest_point(const Vec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshnbv
