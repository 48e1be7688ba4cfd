#include "meshnbv/hull.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace meshnbv {

namespace {

// Four well-spread points spanning space (indices into p), or false when
// the points span less than three dimensions (see convex_hull_triangles).
bool initial_tetrahedron(const std::vector<Vec3>& p, std::array<std::size_t, 4>* t, double* extent) {
  if (p.size() < 4) return false;
  std::size_t a = 0, b = 0, c = 0, d = 0;
  double best = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - p[0]).squaredNorm() > best) best = (p[i] - p[0]).squaredNorm(), a = i;
  *extent = std::sqrt(best);
  if (!(*extent > 0)) return false;
  best = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - p[a]).squaredNorm() > best) best = (p[i] - p[a]).squaredNorm(), b = i;
  *extent = std::max(*extent, std::sqrt(best));
  const Vec3 axis = (p[b] - p[a]).normalized();
  best = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double s = (p[i] - p[a]).cross(axis).squaredNorm();
    if (s > best) best = s, c = i;
  }
  if (!(std::sqrt(best) > 1e-9 * *extent)) return false;
  const Vec3 n = (p[b] - p[a]).cross(p[c] - p[a]).normalized();
  best = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double s = std::abs((p[i] - p[a]).dot(n));
    if (s > best) best = s, d = i;
  }
  if (!(best > 1e-9 * *extent)) return false;
  *t = {a, b, c, d};
  return true;
}

struct HullFace {
  std::array<std::uint32_t, 3> v;  // counter-clockwise seen from outside
  Vec3 normal;                     // unit, outward
  double offset;                   // normal . x on the plane
  bool alive = true;
};

HullFace make_face(const std::vector<Vec3>& p, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  HullFace f;
  f.v = {a, b, c};
  const Vec3 cross = (p[b] - p[a]).cross(p[c] - p[a]);
  const double norm = cross.norm();
  f.normal = norm > 0 ? Vec3(cross / norm) : Vec3(0, 0, 0);
  f.offset = f.normal.dot(p[a]);
  return f;
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) { return std::uint64_t(a) << 32 | b; }

}  // namespace

// Incremental construction: a tetrahedron of well-spread points, then each
// point that lies outside the current hull (beyond some face's plane by
// more than the tolerance) removes the faces it sees and joins the
// horizon's edges. O(n h) for h hull faces; points inside cost one pass
// over the faces.
std::vector<HullTriangle> convex_hull_triangles(const std::vector<Vec3>& points) {
  std::vector<HullTriangle> out;
  std::array<std::size_t, 4> t;
  double extent = 0;
  if (!initial_tetrahedron(points, &t, &extent)) return out;
  const double eps = 1e-12 * extent;
  std::vector<HullFace> faces;
  {
    const auto [a, b, c, d] = t;
    std::uint32_t A = std::uint32_t(a), B = std::uint32_t(b), C = std::uint32_t(c), D = std::uint32_t(d);
    // Orient (A, B, C) away from D.
    if ((points[B] - points[A]).cross(points[C] - points[A]).dot(points[D] - points[A]) > 0) std::swap(B, C);
    faces = {make_face(points, A, B, C), make_face(points, A, D, B), make_face(points, B, D, C),
             make_face(points, C, D, A)};
  }
  std::vector<std::size_t> visible;
  std::unordered_map<std::uint64_t, char> edges;
  std::size_t dead = 0;  // faces marked dead since the last compaction
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i == t[0] || i == t[1] || i == t[2] || i == t[3]) continue;
    const Vec3& q = points[i];
    visible.clear();
    for (std::size_t f = 0; f < faces.size(); ++f)
      if (faces[f].alive && faces[f].normal.dot(q) - faces[f].offset > eps) visible.push_back(f);
    if (visible.empty()) continue;  // inside or on the hull
    // The horizon: edges of seen faces whose other side is not seen.
    edges.clear();
    for (std::size_t f : visible)
      for (int k = 0; k < 3; ++k) edges[edge_key(faces[f].v[k], faces[f].v[(k + 1) % 3])] = 1;
    std::vector<std::array<std::uint32_t, 2>> horizon;
    for (std::size_t f : visible) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = faces[f].v[k], b = faces[f].v[(k + 1) % 3];
        if (!edges.count(edge_key(b, a))) horizon.push_back({a, b});
      }
      faces[f].alive = false;
    }
    for (const auto& [a, b] : horizon) faces.push_back(make_face(points, a, b, std::uint32_t(i)));
    // Drop dead faces now and then, so that the scans stay short.
    dead += visible.size();
    if (faces.size() > 64 && 2 * dead > faces.size()) {
      faces.erase(std::remove_if(faces.begin(), faces.end(), [](const HullFace& f) { return !f.alive; }),
                  faces.end());
      dead = 0;
    }
  }
  for (const HullFace& f : faces)
    if (f.alive) out.push_back({points[f.v[0]], points[f.v[1]], points[f.v[2]]});
  return out;
}

}  // namespace meshnbv
