// The one translation unit with CGAL's AABB tree (slow to compile).
#include "meshnbv/surface_distance.h"

#include <cmath>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#pragma GCC diagnostic pop

#include "meshnbv/error.h"

namespace meshnbv {
namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point3 = Kernel::Point_3;
using Triangle3 = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
Point3 to_cgal(const Vec3& p) { return Point3(p.x(), p.y(), p.z()); }
}  // namespace

struct SurfaceDistance::Impl {
  std::vector<Triangle3> triangles;
  AabbTree tree;
};

SurfaceDistance::SurfaceDistance(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  mesh.validate();
  impl_->triangles.reserve(mesh.num_faces());
  for (const Face& f : mesh.faces) {
    Triangle3 t(to_cgal(mesh.vertices[f[0]]), to_cgal(mesh.vertices[f[1]]),
                to_cgal(mesh.vertices[f[2]]));
    // Degenerate triangles have no area and upset CGAL's closest-point code.
    if (!t.is_degenerate()) impl_->triangles.push_back(t);
  }
  if (impl_->triangles.empty()) throw Error("the surface has no non-degenerate face");
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();  // const and thread-safe from here on
}

SurfaceDistance::~SurfaceDistance() = default;

double SurfaceDistance::distance(const Vec3& p) const {
  return std::sqrt(impl_->tree.squared_distance(to_cgal(p)));
}

Vec3 SurfaceDistance::closest_point(const Vec3& p) const {
  const Point3 q = impl_->tree.closest_point(to_cgal(p));
  return Vec3(q.x(), q.y(), q.z());
}

}  // namespace meshnbv
