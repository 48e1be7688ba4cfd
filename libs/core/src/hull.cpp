#include "meshnbv/hull.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

namespace meshnbv {

namespace {

// True when the points span three dimensions: some point lies farther than
// 1e-9 of the extent from the plane of three well-spread ones.
bool spans_space(const std::vector<Vec3>& p) {
  if (p.size() < 4) return false;
  std::size_t a = 0, b = 0, c = 0;
  double best = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - p[0]).squaredNorm() > best) best = (p[i] - p[0]).squaredNorm(), a = i;
  const double extent = std::sqrt(best);
  if (!(extent > 0)) return false;
  best = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - p[a]).squaredNorm() > best) best = (p[i] - p[a]).squaredNorm(), b = i;
  const Vec3 axis = (p[b] - p[a]).normalized();
  best = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = (p[i] - p[a]).cross(axis).squaredNorm();
    if (d > best) best = d, c = i;
  }
  if (!(std::sqrt(best) > 1e-9 * extent)) return false;
  const Vec3 n = (p[b] - p[a]).cross(p[c] - p[a]).normalized();
  for (const Vec3& q : p)
    if (std::abs((q - p[a]).dot(n)) > 1e-9 * extent) return true;
  return false;
}

}  // namespace

std::vector<HullTriangle> convex_hull_triangles(const std::vector<Vec3>& points) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = K::Point_3;
  std::vector<HullTriangle> out;
  if (!spans_space(points)) return out;
  std::vector<Point> p;
  p.reserve(points.size());
  for (const Vec3& v : points) p.emplace_back(v.x(), v.y(), v.z());
  CGAL::Surface_mesh<Point> hull;
  CGAL::convex_hull_3(p.begin(), p.end(), hull);
  for (auto f : hull.faces()) {
    HullTriangle t;
    int k = 0;
    for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
      if (k < 3) {
        const Point& q = hull.point(v);
        t[std::size_t(k)] = Vec3(q.x(), q.y(), q.z());
      }
      ++k;
    }
    if (k == 3) out.push_back(t);
  }
  return out;
}

}  // namespace meshnbv
