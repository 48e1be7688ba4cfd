// Degradations of a ground-truth mesh and the per-face ground-truth error.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

#include "meshnbv/error.h"
#include "meshnbv/mesh.h"
#include "meshnbv/synth/degrade.h"
#include "test_util.h"

using namespace meshnbv;
using namespace meshnbv::synth;

namespace {

// Icosphere of `radius` around `center`: 20 * 4^levels faces, welded, outward.
TriangleMesh icosphere(int levels, double radius = 1.0, const Vec3& center = Vec3::Zero()) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  for (const Vec3& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                        Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                        Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.vertices.push_back(p.normalized());
  m.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int id = static_cast<int>(m.vertices.size()) - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<Face> next;
    for (const Face& f : m.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    m.faces = std::move(next);
  }
  for (Vec3& v : m.vertices) v = center + radius * v;
  return m;
}

// Closed axis-aligned box from `lo` with edge `size`, each side an n x n grid
// (welded, outward).
TriangleMesh grid_box(const Vec3& lo, double size, int n) {
  TriangleMesh m;
  std::map<std::tuple<long, long, long>, int> ids;
  auto vertex = [&](const Vec3& unit) {  // unit in [0,1]^3
    const auto key = std::make_tuple(std::lround(unit.x() * n), std::lround(unit.y() * n),
                                     std::lround(unit.z() * n));
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    m.vertices.push_back(lo + size * Vec3(double(std::get<0>(key)) / n,
                                          double(std::get<1>(key)) / n,
                                          double(std::get<2>(key)) / n));
    const int id = static_cast<int>(m.vertices.size()) - 1;
    ids.emplace(key, id);
    return id;
  };
  const Vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1), O(0, 0, 0);
  // origin, u, v with u x v outward
  const std::array<std::array<Vec3, 3>, 6> sides = {
      {{O, Y, X}, {Z, X, Y}, {O, X, Z}, {Y, Z, X}, {O, Z, Y}, {X, Y, Z}}};
  for (const auto& side : sides)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        auto at = [&](int a, int b) {
          return vertex(side[0] + (double(a) / n) * side[1] + (double(b) / n) * side[2]);
        };
        const int p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
        m.faces.push_back({p00, p10, p11});
        m.faces.push_back({p00, p11, p01});
      }
  return m;
}

// Flat square [0,size]^2 at z = 0, n x n cells, normal +z.
TriangleMesh flat_square(double size, int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(size * i / n, size * j / n, 0.0);
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

double diagonal(const TriangleMesh& m) { return m.bounding_box().diagonal(); }

bool bitwise_equal(const Vec3& a, const Vec3& b) {
  return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
}

// Index of the vertex with the largest z.
int top_vertex(const TriangleMesh& m) {
  int best = 0;
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    if (m.vertices[v].z() > m.vertices[best].z()) best = static_cast<int>(v);
  return best;
}

Degradation make(DegradationKind kind, double strength, double radius,
                 const Vec3& center = Vec3::Constant(std::numeric_limits<double>::quiet_NaN())) {
  Degradation d;
  d.kind = kind;
  d.strength = strength;
  d.radius = radius;
  d.center = center;
  return d;
}

}  // namespace

// ---------------------------------------------------------------------------
// parse_degradation

TEST(DegradationParse, DefaultsAndFields) {
  Degradation d = parse_degradation("noise");
  EXPECT_EQ(d.kind, DegradationKind::Noise);
  EXPECT_DOUBLE_EQ(d.strength, 0.005);
  EXPECT_DOUBLE_EQ(d.radius, 0.15);
  EXPECT_FALSE(d.center.allFinite());

  d = parse_degradation("noise:0.01:0.2");
  EXPECT_DOUBLE_EQ(d.strength, 0.01);
  EXPECT_DOUBLE_EQ(d.radius, 0.2);

  d = parse_degradation("dent");
  EXPECT_EQ(d.kind, DegradationKind::Dent);
  EXPECT_DOUBLE_EQ(d.strength, 0.02);
  EXPECT_DOUBLE_EQ(d.radius, 0.15);
  d = parse_degradation("bump:0.03");
  EXPECT_EQ(d.kind, DegradationKind::Bump);
  EXPECT_DOUBLE_EQ(d.strength, 0.03);
  EXPECT_DOUBLE_EQ(d.radius, 0.15);
  d = parse_degradation("hole");
  EXPECT_EQ(d.kind, DegradationKind::Hole);
  EXPECT_DOUBLE_EQ(d.radius, 0.08);
  d = parse_degradation("hole:0:0.1");
  EXPECT_DOUBLE_EQ(d.radius, 0.1);
  d = parse_degradation("decimate");
  EXPECT_EQ(d.kind, DegradationKind::Decimate);
  EXPECT_DOUBLE_EQ(d.strength, 0.8);
  d = parse_degradation("decimate:0.9");
  EXPECT_DOUBLE_EQ(d.strength, 0.9);
  d = parse_degradation("decimate:0");
  EXPECT_DOUBLE_EQ(d.strength, 0.0);
  d = parse_degradation("noise:1e-3");
  EXPECT_DOUBLE_EQ(d.strength, 0.001);

  for (auto kind : {DegradationKind::Noise, DegradationKind::Dent, DegradationKind::Bump,
                    DegradationKind::Hole, DegradationKind::Decimate})
    EXPECT_EQ(parse_degradation(degradation_name(kind)).kind, kind);
  EXPECT_EQ(degradation_name(DegradationKind::Bump), "bump");
}

TEST(DegradationParse, BadInputs) {
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("blur"), "unknown degradation 'blur'");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation(""), "unknown degradation ''");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("Noise"), "unknown degradation");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:abc"), "strength 'abc' is not a number");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:0.1x"), "is not a number");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise: 0.1"), "is not a number");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:nan"), "is not a number");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:inf"), "is not a number");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:"), "empty strength");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:0.1:r"), "radius 'r' is not a number");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("dent:-0.1"), "strength must be a non-negative");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("bump:0.1:-1"), "radius must be a positive");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("hole:0:0"), "radius must be a positive");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("decimate:1"), "must be in [0, 1)");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("decimate:1.5"), "must be in [0, 1)");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("decimate:-0.1"), "non-negative");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("decimate:0.5:0.1"), "decimate takes no radius");
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_degradation("noise:0.1:0.1:3"), "too many ':' fields");
}

// ---------------------------------------------------------------------------
// face_distance_to_surface

TEST(DistanceToSurface, SelfIsZero) {
  const TriangleMesh sphere = icosphere(3);
  const double diag = diagonal(sphere);
  const std::vector<float> d = face_distance_to_surface(sphere, sphere, 3);
  ASSERT_EQ(d.size(), sphere.num_faces());
  const float worst = *std::max_element(d.begin(), d.end());
  EXPECT_LT(worst, 1e-9 * diag);
  EXPECT_GE(*std::min_element(d.begin(), d.end()), 0.0f);
}

TEST(DistanceToSurface, TranslatedSquareIsOffset) {
  const TriangleMesh square = flat_square(10.0, 20);
  TriangleMesh moved = square;
  const Vec3 normal = square.face_normal(0);
  ASSERT_NEAR(normal.z(), 1.0, 1e-12);
  for (Vec3& v : moved.vertices) v += 0.1 * normal;
  for (int samples : {0, 1, 3, 5}) {
    const std::vector<float> d = face_distance_to_surface(moved, square, samples);
    ASSERT_EQ(d.size(), moved.num_faces());
    for (std::size_t f = 0; f < d.size(); ++f) {
      const Vec3 c = moved.face_centroid(f);
      const bool interior = c.x() > 0.5 && c.x() < 9.5 && c.y() > 0.5 && c.y() < 9.5;
      if (interior) {
        ASSERT_NEAR(d[f], 0.1, 1e-6) << "face " << f << " samples " << samples;
      }
    }
  }
  // Off the side of the square: a face beyond x = 10 by 1, at height 0.
  TriangleMesh side;
  side.vertices = {Vec3(11, 5, 0), Vec3(11, 6, 0), Vec3(11, 5, 1)};
  side.faces = {{0, 1, 2}};
  const std::vector<float> ds = face_distance_to_surface(side, square, 1);
  // Samples: the three corners; distances 1, 1, sqrt(2).
  EXPECT_NEAR(ds[0], (2.0 + std::sqrt(2.0)) / 3.0, 1e-6);
}

TEST(DistanceToSurface, ErrorsAndEmpty) {
  const TriangleMesh square = flat_square(1.0, 2);
  MESHNBV_EXPECT_ERROR_CONTAINS(face_distance_to_surface(square, TriangleMesh(), 3),
                                "ground-truth mesh has no faces");
  MESHNBV_EXPECT_ERROR_CONTAINS(face_distance_to_surface(square, square, -1),
                                "samples_per_side must be >= 0");
  EXPECT_TRUE(face_distance_to_surface(TriangleMesh(), square, 3).empty());
}

// ---------------------------------------------------------------------------
// degrade

TEST(Degrade, NoiseChangesOnlyTheRegion) {
  const TriangleMesh truth = icosphere(5);  // 20480 faces
  const double diag = diagonal(truth);
  const Degradation noise = parse_degradation("noise:0.01:0.2");
  const DegradeResult out = degrade(truth, {noise}, 7);
  ASSERT_EQ(out.region_centers.size(), 1u);
  const Vec3 c = out.region_centers[0];
  // On the surface (within the chord sagitta of the level-5 icosphere) and
  // on a face not pointing down.
  EXPECT_NEAR(c.norm(), 1.0, 2e-3);
  EXPECT_GT(c.z(), -0.55);
  const double r = 0.2 * diag;
  ASSERT_EQ(out.mesh.num_vertices(), truth.num_vertices());
  ASSERT_EQ(out.mesh.faces, truth.faces);
  std::size_t inside = 0, moved = 0;
  for (std::size_t v = 0; v < truth.num_vertices(); ++v) {
    const double dist = (truth.vertices[v] - c).norm();
    if (dist >= r) {
      ASSERT_TRUE(bitwise_equal(out.mesh.vertices[v], truth.vertices[v])) << "vertex " << v;
    } else {
      ++inside;
      if (!bitwise_equal(out.mesh.vertices[v], truth.vertices[v])) ++moved;
      // Only along the normal (the sphere's normal is radial, up to facet tilt).
      const Vec3 delta = out.mesh.vertices[v] - truth.vertices[v];
      EXPECT_LT(delta.cross(truth.vertices[v]).norm(), 0.02 * delta.norm() + 1e-15);
    }
  }
  EXPECT_GT(inside, 100u);
  EXPECT_EQ(moved, inside);

  const std::vector<float> err = face_distance_to_surface(out.mesh, truth, 3);
  double inner_sum = 0, inner_n = 0, far_max = 0;
  for (std::size_t f = 0; f < truth.num_faces(); ++f) {
    const double dist = (truth.face_centroid(f) - c).norm();
    if (dist < 0.5 * r) {
      EXPECT_GT(err[f], 0.0f) << "face " << f;
      inner_sum += err[f];
      ++inner_n;
    } else if (dist > r + 0.1) {
      far_max = std::max(far_max, double(err[f]));
    }
  }
  const double inner_mean = inner_sum / inner_n;
  std::printf(
      "[noise] region vertices %zu, mean GT error inside r/2 = %.3g (sigma %.3g), far max = %.3g\n",
      inside, inner_mean, 0.01 * diag, far_max);
  EXPECT_GT(inner_mean, 0.1 * 0.01 * diag);
  EXPECT_LT(far_max, 1e-9 * diag);
}

TEST(Degrade, NoiseDoesNotCrackTouchingComponents) {
  // Two closed boxes sharing the plane x = 1 with coincident but unshared
  // vertices; the region straddles the contact.
  TriangleMesh truth = grid_box(Vec3(0, 0, 0), 1.0, 8);
  truth.append(grid_box(Vec3(1, 0, 0), 1.0, 8));
  Degradation noise = make(DegradationKind::Noise, 0.02, 0.3, Vec3(1, 0.5, 1));
  const DegradeResult out = degrade(truth, {noise}, 3);
  const int half = static_cast<int>(truth.num_vertices() / 2);
  std::size_t coincident = 0, moved = 0;
  for (int a = 0; a < half; ++a)
    for (int b = half; b < 2 * half; ++b)
      if (bitwise_equal(truth.vertices[a], truth.vertices[b])) {
        ++coincident;
        EXPECT_TRUE(bitwise_equal(out.mesh.vertices[a], out.mesh.vertices[b])) << a << " " << b;
        if (!bitwise_equal(out.mesh.vertices[a], truth.vertices[a])) ++moved;
      }
  EXPECT_EQ(coincident, 81u);  // the 9 x 9 grid of the shared side
  EXPECT_GT(moved, 5u);
}

TEST(Degrade, DentAndBumpAlongTheNormal) {
  const TriangleMesh truth = icosphere(4);
  const double diag = diagonal(truth);
  const std::vector<Vec3> normals = truth.vertex_normals();
  const int top = top_vertex(truth);
  const Vec3 center = truth.vertices[top];
  const double strength = 0.03, radius = 0.2, r = radius * diag;
  for (auto kind : {DegradationKind::Dent, DegradationKind::Bump}) {
    const DegradeResult out = degrade(truth, {make(kind, strength, radius, center)}, 1);
    ASSERT_EQ(out.region_centers.size(), 1u);
    EXPECT_TRUE(bitwise_equal(out.region_centers[0], center));
    const double sign = kind == DegradationKind::Dent ? -1.0 : 1.0;
    std::size_t inside = 0;
    for (std::size_t v = 0; v < truth.num_vertices(); ++v) {
      const Vec3 delta = out.mesh.vertices[v] - truth.vertices[v];
      const double along = delta.dot(normals[v]);
      if ((truth.vertices[v] - center).norm() < r) {
        ++inside;
        EXPECT_GT(sign * along, 0.0) << degradation_name(kind) << " vertex " << v;
        EXPECT_NEAR((delta - along * normals[v]).norm(), 0.0, 1e-12);
        EXPECT_LE(std::abs(along), strength * diag * (1 + 1e-12));
      } else {
        ASSERT_TRUE(bitwise_equal(out.mesh.vertices[v], truth.vertices[v]));
      }
    }
    const double peak = (out.mesh.vertices[top] - center).dot(normals[top]);
    std::printf("[%s] %zu vertices moved, peak displacement %.6g (strength*diag %.6g)\n",
                degradation_name(kind).c_str(), inside, peak, strength * diag);
    EXPECT_NEAR(sign * peak, strength * diag, 0.05 * strength * diag);
    EXPECT_GT(inside, 30u);
    // The GT error of the faces at the peak is a good part of the displacement.
    const std::vector<float> err = face_distance_to_surface(out.mesh, truth, 3);
    double max_err = *std::max_element(err.begin(), err.end());
    EXPECT_GT(max_err, 0.5 * strength * diag);
    EXPECT_LE(max_err, strength * diag * 1.01);
  }
}

TEST(Degrade, HoleRemovesFacesInTheBall) {
  TriangleMesh truth = icosphere(4);
  std::vector<float> quality(truth.num_faces());
  truth.face_colors.resize(truth.num_faces());
  for (std::size_t f = 0; f < truth.num_faces(); ++f) {
    quality[f] = static_cast<float>(f);
    truth.face_colors[f] = {static_cast<std::uint8_t>(f % 251), static_cast<std::uint8_t>(f % 13),
                            7};
  }
  truth.set_face_attribute("quality", quality);
  const double diag = diagonal(truth);
  const Vec3 center = truth.vertices[top_vertex(truth)];
  const double radius = 0.1;
  std::size_t expected_removed = 0;
  for (std::size_t f = 0; f < truth.num_faces(); ++f)
    if ((truth.face_centroid(f) - center).norm() < radius * diag) ++expected_removed;
  ASSERT_GT(expected_removed, 10u);

  const DegradeResult out = degrade(truth, {make(DegradationKind::Hole, 0, radius, center)}, 5);
  EXPECT_EQ(out.mesh.num_faces(), truth.num_faces() - expected_removed);
  EXPECT_NO_THROW(out.mesh.validate("hole"));
  const MeshCheck before = check_mesh(truth), after = check_mesh(out.mesh);
  EXPECT_EQ(before.boundary_edges, 0u);
  EXPECT_GT(after.boundary_edges, 0u);
  EXPECT_EQ(after.nonmanifold_edges, 0u);
  EXPECT_EQ(after.unreferenced_vertices, 0u);
  std::printf("[hole] removed %zu of %zu faces, %zu boundary edges\n", expected_removed,
              truth.num_faces(), after.boundary_edges);
  // Survivors keep their attribute, colour and geometry.
  const std::vector<float>* q = out.mesh.face_attribute("quality");
  ASSERT_NE(q, nullptr);
  ASSERT_EQ(out.mesh.face_colors.size(), out.mesh.num_faces());
  for (std::size_t f = 0; f < out.mesh.num_faces(); ++f) {
    const auto original = static_cast<std::size_t>((*q)[f]);
    ASSERT_GE((truth.face_centroid(original) - center).norm(), radius * diag);
    EXPECT_EQ(out.mesh.face_colors[f], truth.face_colors[original]);
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(bitwise_equal(out.mesh.vertices[out.mesh.faces[f][k]],
                                truth.vertices[truth.faces[original][k]]));
  }
}

TEST(Degrade, DecimateSphere) {
  TriangleMesh truth = icosphere(4);  // 5120 faces
  truth.set_face_attribute("quality", std::vector<float>(truth.num_faces(), 1.0f));
  const double diag = diagonal(truth);
  const DegradeResult out = degrade(truth, {parse_degradation("decimate:0.8")}, 11);
  EXPECT_TRUE(out.region_centers.empty());
  const double target = 0.2 * truth.num_faces();
  EXPECT_NEAR(double(out.mesh.num_faces()), target, 0.05 * target);
  EXPECT_NO_THROW(out.mesh.validate("decimated"));
  const MeshCheck check = check_mesh(out.mesh);
  EXPECT_TRUE(check.closed());
  EXPECT_EQ(check.unreferenced_vertices, 0u);
  EXPECT_EQ(check.degenerate_faces, 0u);
  EXPECT_TRUE(out.mesh.face_attributes.empty());  // faces changed: attributes dropped
  EXPECT_TRUE(out.mesh.face_colors.empty());
  const std::vector<float> err = face_distance_to_surface(out.mesh, truth, 3);
  double mean = 0;
  for (float e : err) mean += e;
  mean /= err.size();
  const double worst = *std::max_element(err.begin(), err.end());
  std::printf(
      "[decimate] %zu -> %zu faces (target %.0f), GT error mean %.3g max %.3g (diag %.3g)\n",
      truth.num_faces(), out.mesh.num_faces(), target, mean, worst, diag);
  EXPECT_LT(worst, 0.01 * diag);
  EXPECT_LT(mean, 0.002 * diag);
  // Still outward: the enclosed volume is that of the sphere, give or take.
  double volume = 0;
  for (const Face& f : out.mesh.faces)
    volume +=
        out.mesh.vertices[f[0]].dot(out.mesh.vertices[f[1]].cross(out.mesh.vertices[f[2]])) / 6;
  EXPECT_NEAR(volume, 4.0 / 3.0 * std::acos(-1.0), 0.1);

  // Strength 0 removes nothing: the mesh comes back as it was, attributes too.
  const DegradeResult none = degrade(truth, {parse_degradation("decimate:0")}, 11);
  EXPECT_EQ(none.mesh.faces, truth.faces);
  EXPECT_NE(none.mesh.face_attribute("quality"), nullptr);
}

TEST(Degrade, DecimateComponentsAndNonManifoldFaces) {
  // Two separate closed boxes, plus a fin: a third face on an edge of the
  // first box, which OpenMesh cannot hold.
  TriangleMesh truth = grid_box(Vec3(0, 0, 0), 1.0, 6);
  truth.append(grid_box(Vec3(3, 0, 0), 1.0, 6));
  const int a = truth.faces[0][0], b = truth.faces[0][1];
  truth.vertices.emplace_back(0.5, 0.5, -1.0);
  const int fin_tip = static_cast<int>(truth.num_vertices()) - 1;
  truth.faces.push_back({a, b, fin_tip});
  ASSERT_EQ(check_mesh(truth).nonmanifold_edges, 1u);
  const Vec3 fin_a = truth.vertices[a], fin_b = truth.vertices[b], fin_c = truth.vertices[fin_tip];

  const DegradeResult out = degrade(truth, {parse_degradation("decimate:0.9")}, 2);
  EXPECT_NO_THROW(out.mesh.validate("decimated boxes"));
  const double target = 0.1 * truth.num_faces();
  std::printf("[decimate boxes] %zu -> %zu faces (target %.0f)\n", truth.num_faces(),
              out.mesh.num_faces(), target);
  EXPECT_LT(out.mesh.num_faces(), truth.num_faces() / 4);
  EXPECT_GE(out.mesh.num_faces(), std::size_t(2 * 12 + 1));
  // The fin survives unchanged.
  bool fin_found = false;
  for (const Face& f : out.mesh.faces)
    if (bitwise_equal(out.mesh.vertices[f[0]], fin_a) &&
        bitwise_equal(out.mesh.vertices[f[1]], fin_b) &&
        bitwise_equal(out.mesh.vertices[f[2]], fin_c))
      fin_found = true;
  EXPECT_TRUE(fin_found);
  // Both boxes remain: vertices on either side of x = 2, and the surface is
  // the truth's (flat sides collapse without error).
  const std::vector<float> err = face_distance_to_surface(out.mesh, truth, 3);
  EXPECT_LT(*std::max_element(err.begin(), err.end()), 1e-9);
  std::size_t left = 0, right = 0;
  for (const Vec3& v : out.mesh.vertices) (v.x() < 2 ? left : right)++;
  EXPECT_GE(left, 8u);
  EXPECT_GE(right, 8u);
}

TEST(Degrade, SameSeedSameOutput) {
  const TriangleMesh truth = icosphere(4);
  const std::vector<Degradation> chain = {
      parse_degradation("noise:0.01:0.3"), parse_degradation("dent"), parse_degradation("bump"),
      parse_degradation("hole"), parse_degradation("decimate:0.5")};
  const DegradeResult a = degrade(truth, chain, 42);
  const DegradeResult b = degrade(truth, chain, 42);
  ASSERT_EQ(a.region_centers.size(), 4u);
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  for (std::size_t v = 0; v < a.mesh.num_vertices(); ++v)
    ASSERT_TRUE(bitwise_equal(a.mesh.vertices[v], b.mesh.vertices[v])) << "vertex " << v;
  for (std::size_t i = 0; i < a.region_centers.size(); ++i)
    EXPECT_TRUE(bitwise_equal(a.region_centers[i], b.region_centers[i]));

  const DegradeResult c = degrade(truth, chain, 43);
  EXPECT_GT((a.region_centers[0] - c.region_centers[0]).norm(), 1e-6);
  // Different seeds spread the centres around the (upper part of the) sphere.
  std::size_t distinct = 0;
  Vec3 previous = Vec3::Constant(1e9);
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const Vec3 centre = degrade(truth, {parse_degradation("dent")}, seed).region_centers[0];
    EXPECT_GT(centre.z(), -0.55) << "seed " << seed;
    if ((centre - previous).norm() > 1e-6) ++distinct;
    previous = centre;
  }
  EXPECT_EQ(distinct, 20u);
}

TEST(Degrade, BadInputs) {
  const TriangleMesh sphere = icosphere(1);
  MESHNBV_EXPECT_ERROR_CONTAINS(degrade(TriangleMesh(), {parse_degradation("noise")}, 1),
                                "no faces");
  MESHNBV_EXPECT_ERROR_CONTAINS(degrade(sphere, {make(DegradationKind::Noise, -1, 0.1)}, 1),
                                "strength must be a non-negative");
  MESHNBV_EXPECT_ERROR_CONTAINS(degrade(sphere, {make(DegradationKind::Decimate, 1.0, 0.1)}, 1),
                                "[0, 1)");
  MESHNBV_EXPECT_ERROR_CONTAINS(degrade(sphere, {make(DegradationKind::Hole, 0, 0)}, 1),
                                "radius must be a positive");
  // A hole that swallows everything leaves nothing to place the next region on.
  MESHNBV_EXPECT_ERROR_CONTAINS(
      degrade(sphere, {make(DegradationKind::Hole, 0, 10.0), parse_degradation("dent")}, 1),
      "no face");
  // No degradation: the truth itself.
  const DegradeResult same = degrade(sphere, {}, 9);
  EXPECT_EQ(same.mesh.faces, sphere.faces);
  EXPECT_TRUE(same.region_centers.empty());
}
