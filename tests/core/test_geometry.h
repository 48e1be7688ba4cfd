// Independent geometry for checking the core's answers in tests: written
// here from textbook formulas, sharing no code with the core (no Embree, no
// CGAL), so that a test never checks a result with the code that made it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>

#include "meshnbv/mesh.h"

namespace meshnbv::test {

// A rotation drawn uniformly (a normalised Gaussian quaternion).
inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// Distance from p to the triangle (a, b, c): the closest point by the
// Voronoi regions of the vertices, edges and face (Ericson, Real-Time
// Collision Detection, 5.1.5).
inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// Distance from p to the mesh by brute force over every face.
inline double brute_force_distance(const TriangleMesh& mesh, const Vec3& p) {
  double d = std::numeric_limits<double>::infinity();
  for (const Face& f : mesh.faces)
    d = std::min(d, point_triangle_distance(p, mesh.vertices[std::size_t(f[0])],
                                            mesh.vertices[std::size_t(f[1])],
                                            mesh.vertices[std::size_t(f[2])]));
  return d;
}

// Generalised winding number of the (outward-oriented) mesh around p: the
// sum of the faces' signed solid angles over 4 pi (Van Oosterom and
// Strackee's formula). For a union of closed components it counts the
// components that contain p: 0 outside, 1 inside one.
inline double winding_number(const TriangleMesh& mesh, const Vec3& p) {
  double sum = 0;
  for (const Face& f : mesh.faces) {
    const Vec3 a = mesh.vertices[std::size_t(f[0])] - p, b = mesh.vertices[std::size_t(f[1])] - p,
               c = mesh.vertices[std::size_t(f[2])] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * M_PI);
}

// Inside the axis-aligned box [lo, hi] (closed interval test).
inline bool in_box(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

// Distance from p to the surface of the box [lo, hi] (zero on it).
inline double box_surface_distance(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  if (in_box(p, lo, hi))
    return std::min({p.x() - lo.x(), hi.x() - p.x(), p.y() - lo.y(), hi.y() - p.y(),
                     p.z() - lo.z(), hi.z() - p.z()});
  const Vec3 q = p.cwiseMax(lo).cwiseMin(hi);
  return (p - q).norm();
}

}  // namespace meshnbv::test
