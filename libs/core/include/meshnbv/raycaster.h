// Ray casting against a triangle mesh with Embree 3. Thread-safe queries.
// Coordinates are shifted to the mesh's bounding-box centre before they go
// to Embree (single precision), so meshes in large world coordinates
// (e.g. UTM) keep their precision.
#pragma once

#include <limits>
#include <memory>

#include "meshnbv/mesh.h"

namespace meshnbv {

struct RayHit {
  double distance = 0;  // along the (unit) direction
  int face = -1;
  double u = 0, v = 0;  // barycentric: point = (1-u-v) V0 + u V1 + v V2
};

class RayCaster {
 public:
  // Builds the acceleration structure (the mesh must be valid).
  explicit RayCaster(const TriangleMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Nearest hit with distance in (t_min, t_max); `direction` need not be unit.
  bool intersect(const Vec3& origin, const Vec3& direction, RayHit* hit, double t_min = 0.0,
                 double t_max = std::numeric_limits<double>::infinity()) const;
  // True when any face is hit with distance in (t_min, t_max).
  bool occluded(const Vec3& origin, const Vec3& direction, double t_min, double t_max) const;
  // True when nothing blocks the segment from `from` to `to`, up to
  // (1 - relative_eps) of its length minus `absolute_eps` (SPEC section 2).
  bool segment_clear(const Vec3& from, const Vec3& to, double relative_eps,
                     double absolute_eps) const;
  // segment_clear for the four segments from `from` to `to[0..3]`, traced
  // together as one Embree packet (coherent rays from one camera centre).
  bool segments_clear4(const Vec3& from, const Vec3 (&to)[4], double relative_eps,
                       double absolute_eps) const;

  // Distance from `p` to the nearest point of the surface (Embree's BVH
  // point query, exact closest point per triangle in double precision);
  // the point and its face are returned when asked. Throws Error for a mesh
  // without faces or a non-finite point.
  double closest_point(const Vec3& p, Vec3* point = nullptr, int* face = nullptr) const;

  const Vec3& offset() const { return offset_; }

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  Vec3 offset_;
};

}  // namespace meshnbv
