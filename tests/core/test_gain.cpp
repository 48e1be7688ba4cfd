// The whole-mesh energy (gain.h): its formula checked against values
// written out here, one edge case per test, and the planner's batches.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "meshnbv/error.h"
#include "meshnbv/gain.h"
#include "meshnbv/hull.h"
#include "meshnbv/planner.h"
#include "meshnbv/raycaster.h"

using namespace meshnbv;

namespace gain_test {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The square [-1, 1]^2 at z = 0, normal +z, as n x n cells of two triangles.
TriangleMesh square(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back(Vec3(-1 + 2.0 * i / n, -1 + 2.0 * j / n, 0));
  auto at = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// The closed cube [-1, 1]^3, outward normals.
TriangleMesh cube() {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) m.vertices.push_back(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

PinholeCamera looking(const Vec3& eye, const Vec3& target) {
  const Vec3 up = std::abs((target - eye).normalized().z()) > 0.9 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  return PinholeCamera::look_at(eye, target, up, 500, 500, 319.5, 239.5, 640, 480);
}

double sigmoid(double x, double x0, double k) { return 1 / (1 + std::exp(-k * (x - x0))); }

// g's maximum over angles, by a fine scan.
double g_max() {
  double best = 0;
  for (int i = 0; i <= 200000; ++i) best = std::max(best, pair_angle_score(M_PI * i / 200000));
  return best;
}

double angle(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)); }

}  // namespace gain_test

TEST(Gain, PairScoreIsSmithsProductOfSigmoids) {
  for (double deg : {0.0, 5.0, 11.25, 20.0, 45.0, 90.0, 180.0}) {
    const double a = deg * M_PI / 180;
    const double match = 1 - 1 / (1 + std::exp(-8 * (a - M_PI / 4)));
    const double tri = 1 / (1 + std::exp(-32 * (a - M_PI / 16)));
    EXPECT_NEAR(pair_angle_score(a), match * tri, 1e-15) << deg;
  }
  // Small baselines and wide ones both score low; the peak lies between.
  EXPECT_LT(pair_angle_score(0.0), 0.01);
  EXPECT_LT(pair_angle_score(M_PI / 2), 0.01);
  EXPECT_GT(pair_angle_score(20 * M_PI / 180), 0.9);
}

TEST(Gain, NamesReadBack) {
  EXPECT_EQ(parse_energy_kind("paper"), EnergyKind::Paper);
  EXPECT_EQ(energy_kind_name(parse_energy_kind("reconstructability")), "reconstructability");
  EXPECT_THROW(parse_energy_kind("whole"), Error);
}

// Two faces of a square, one existing view above it, a candidate at an
// angle: every face's reconstructability, gain and the energy from the
// formula of gain.h, written out here.
TEST(Gain, EnergyMatchesTheFormulaOnAPlane) {
  const TriangleMesh mesh = gain_test::square(1);
  const RayCaster caster(mesh);
  const PinholeCamera a = gain_test::looking(Vec3(0.1, 0.2, 4), Vec3(0, 0, 0));
  const PinholeCamera b = gain_test::looking(Vec3(1.5, 0.3, 3.5), Vec3(0, 0, 0));
  GainOptions o;
  o.clusters = 0;  // every face on its own
  o.target = 3;
  const GainEvaluator gain(mesh, caster, {gain_test::kNaN, gain_test::kNaN}, {a}, o);
  ASSERT_EQ(gain.num_clusters(), 2u);
  // d_max: twice the farthest existing view of a face.
  double far = 0;
  for (std::size_t f = 0; f < 2; ++f) far = std::max(far, (a.center() - mesh.face_centroid(f)).norm());
  EXPECT_NEAR(gain.max_distance(), 2 * far, 1e-12);
  const double dmax = 2 * far, gm = gain_test::g_max();
  double expected = 0;
  for (std::size_t f = 0; f < 2; ++f) {
    const Vec3 p = mesh.face_centroid(f);
    const double ca = (a.center() - p).normalized().z(), cb = (b.center() - p).normalized().z();
    const double sa = 1 - (a.center() - p).norm() / dmax, sb = 1 - (b.center() - p).norm() / dmax;
    const double h = 0.5 * gm * ca * sa;  // one view: the first-view credit
    const double alpha = gain_test::angle(a.center() - p, b.center() - p);
    const double match = 1 - gain_test::sigmoid(alpha, M_PI / 4, 8), tri = gain_test::sigmoid(alpha, M_PI / 16, 32);
    // The increment, times the novelty of b's ray against a's (the only one).
    const double dh = tri * (match * tri * std::min(ca, cb) * std::min(sa, sb) + 0.5 * gm * std::max(0.0, cb * sb - ca * sa));
    const double before = std::max(3 - h, 0.0), after = std::max(3 - h - dh, 0.0);
    // Both faces are on the boundary: exploration weight 1, half the area each.
    expected += 0.5 * (before * before - after * after) / 9;
    EXPECT_NEAR(gain.face_reconstructability()[f], h, 1e-6) << f;
  }
  const EnergyTerms t = gain.evaluate(b);
  EXPECT_TRUE(t.whole_mesh);
  EXPECT_NEAR(t.total, expected, 1e-4 * expected);
  EXPECT_NEAR(t.exploration, t.total, 1e-15);
  EXPECT_EQ(t.refinement, 0.0);
  EXPECT_EQ(t.occlusion + t.focus + t.parallax + t.incidence, 0.0);
  // The per-cluster gains add up to the energy.
  double sum = 0;
  for (const auto& [c, g] : gain.cluster_gains(b)) sum += g;
  EXPECT_NEAR(sum, t.total, 1e-12);
}

TEST(Gain, ObservedFacesWeighTheirPriRank) {
  const TriangleMesh mesh = gain_test::cube();  // closed: no boundary face
  const RayCaster caster(mesh);
  std::vector<float> pri(12);
  for (int f = 0; f < 12; ++f) pri[std::size_t(f)] = float(f % 6);  // pairs of ties
  pri[11] = gain_test::kNaN;
  GainOptions o;
  o.clusters = 0;
  o.exploration_weight = 2.5;
  const GainEvaluator gain(mesh, caster, pri, {gain_test::looking(Vec3(0, -6, 0.5), Vec3(0, 0, 0))}, o);
  // 11 observed faces; value v (0..5) is held by faces v and v + 6 (5 only by face 5).
  for (int f = 0; f < 11; ++f) {
    const int v = f % 6;
    const double rank = v < 5 ? 2 * v + 1.5 : 11;  // mean of the ranks 2v+1, 2v+2; the single 5 is the 11th
    EXPECT_NEAR(gain.face_weights()[std::size_t(f)], rank / 11, 1e-6) << f;
  }
  EXPECT_FLOAT_EQ(gain.face_weights()[11], 2.5f);
}

TEST(Gain, BoundaryFacesExplore) {
  const TriangleMesh mesh = gain_test::square(4);
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), 0.5f);
  GainOptions o;
  o.clusters = 0;
  o.exploration_weight = 3;
  const GainEvaluator gain(mesh, caster, pri, {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0))}, o);
  // A boundary face has an edge on the square's border (both ends on one side).
  auto on_side = [&](int a, int b) {
    const Vec3 &p = mesh.vertices[std::size_t(a)], &q = mesh.vertices[std::size_t(b)];
    for (int k = 0; k < 2; ++k)
      for (double s : {-1.0, 1.0})
        if (p[k] == s && q[k] == s) return true;
    return false;
  };
  int expected = 0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Face& t = mesh.faces[f];
    const bool boundary = on_side(t[0], t[1]) || on_side(t[1], t[2]) || on_side(t[2], t[0]);
    expected += boundary;
    // One value for all 32 observed faces: they share the mean rank 16.5 of 32.
    EXPECT_FLOAT_EQ(gain.face_weights()[f], boundary ? 3.0f : 16.5f / 32) << f;
  }
  EXPECT_GT(expected, 0);
  EXPECT_LT(expected, int(mesh.num_faces()));
}

TEST(Gain, NothingBeyondTheTarget) {
  const TriangleMesh mesh = gain_test::square(2);
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  GainOptions o;
  o.clusters = 0;
  o.target = 0.05;  // one good pair reaches it
  const std::vector<PinholeCamera> existing = {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0)),
                                               gain_test::looking(Vec3(1.4, 0, 3.8), Vec3(0, 0, 0))};
  const GainEvaluator gain(mesh, caster, pri, existing, o);
  for (float h : gain.face_reconstructability()) EXPECT_GE(h, 0.05f);
  EXPECT_EQ(gain.evaluate(gain_test::looking(Vec3(-1.4, 0.2, 3.8), Vec3(0, 0, 0))).total, 0.0);
  for (float d : gain.face_deficits()) EXPECT_EQ(d, 0.0f);
}

TEST(Gain, OccludedGrazingAndFarViewsGainNothing) {
  TriangleMesh mesh = gain_test::square(2);
  const std::size_t plane_faces = mesh.num_faces();
  const std::vector<PinholeCamera> existing = {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0))};
  const PinholeCamera candidate = gain_test::looking(Vec3(1.5, 0, 3.5), Vec3(0, 0, 0));
  // A roof over the whole square, between it and the candidate (not the existing view: it is below).
  TriangleMesh roofed = mesh;
  const int v = int(roofed.vertices.size());
  // At z = 2.5 the candidate's rays to the square pass x in [0.79, 1.36],
  // the existing view's x in [-0.38, 0.38].
  for (const Vec3& p : {Vec3(0.6, -3, 2.5), Vec3(2, -3, 2.5), Vec3(2, 3, 2.5), Vec3(0.6, 3, 2.5)})
    roofed.vertices.push_back(p);
  roofed.faces.push_back({v, v + 2, v + 1});
  roofed.faces.push_back({v, v + 3, v + 2});
  GainOptions o;
  o.clusters = 0;
  {
    const RayCaster caster(mesh);
    const GainEvaluator open(mesh, caster, std::vector<float>(plane_faces, gain_test::kNaN), existing, o);
    EXPECT_GT(open.evaluate(candidate).total, 0.0);
    // At 87 degrees of incidence (beyond 85) and farther than d_max.
    // 86-88 degrees from the normal over the whole square.
    EXPECT_EQ(open.evaluate(gain_test::looking(Vec3(5, 0, 5 * std::tan(3 * M_PI / 180)), Vec3(0, 0, 0))).total, 0.0);
    EXPECT_EQ(open.evaluate(gain_test::looking(Vec3(0, 0, 2.05 * open.max_distance()), Vec3(0, 0, 0))).total, 0.0);
  }
  const RayCaster caster(roofed);
  std::vector<float> pri(roofed.num_faces(), gain_test::kNaN);
  const GainEvaluator covered(roofed, caster, pri, existing, o);
  const EnergyTerms t = covered.evaluate(candidate);
  for (const auto& [c, g] : covered.cluster_gains(candidate))
    EXPECT_GE(covered.cluster_faces(std::size_t(c))[0], int(plane_faces)) << "a plane face seen through the roof";
  EXPECT_GE(t.total, 0.0);
  // Every face of the plane still counts the existing view (not occluded).
  for (std::size_t f = 0; f < plane_faces; ++f) EXPECT_GT(covered.face_reconstructability()[f], 0.0f) << f;
}

TEST(Gain, AddedViewsGiveDiminishingReturns) {
  const TriangleMesh mesh = gain_test::square(8);
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  GainOptions o;
  o.clusters = 0;
  GainEvaluator gain(mesh, caster, pri, {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0))}, o);
  const PinholeCamera b = gain_test::looking(Vec3(1.4, 0, 3.8), Vec3(0, 0, 0));
  const PinholeCamera c = gain_test::looking(Vec3(1.3, 0.4, 3.8), Vec3(0, 0, 0));
  const double before = gain.evaluate(c).total;
  const double b_alone = gain.evaluate(b).total;
  gain.add_view(b);
  const double after = gain.evaluate(c).total;
  EXPECT_GT(before, 0.0);
  EXPECT_LT(after, before);
  EXPECT_GT(after, 0.0);  // c still adds pairs with both views
  EXPECT_LT(gain.evaluate(b).total, 0.1 * b_alone);  // the same pose again: a pair of almost zero angle
}

TEST(Gain, ClustersApproximateTheFaces) {
  const TriangleMesh mesh = gain_test::square(32);  // 2048 faces
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  const std::vector<PinholeCamera> existing = {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0))};
  GainOptions exact;
  exact.clusters = 0;
  GainOptions coarse;
  coarse.clusters = 96;
  const GainEvaluator e(mesh, caster, pri, existing, exact), c(mesh, caster, pri, existing, coarse);
  EXPECT_EQ(e.num_clusters(), mesh.num_faces());
  EXPECT_LE(c.num_clusters(), 96u);
  EXPECT_GE(c.num_clusters(), 16u);
  std::size_t faces = 0;
  for (std::size_t k = 0; k < c.num_clusters(); ++k) faces += c.cluster_faces(k).size();
  EXPECT_EQ(faces, mesh.num_faces());
  for (const Vec3& eye : {Vec3(1.5, 0, 3.5), Vec3(-2, 1, 3), Vec3(0.3, -1.8, 2.5)}) {
    const double x = e.evaluate(gain_test::looking(eye, Vec3(0, 0, 0))).total, y = c.evaluate(gain_test::looking(eye, Vec3(0, 0, 0))).total;
    EXPECT_NEAR(y, x, 0.05 * x) << eye.transpose();
  }
}

TEST(Gain, MismatchedPriIsAnError) {
  const TriangleMesh mesh = gain_test::square(1);
  const RayCaster caster(mesh);
  EXPECT_THROW(GainEvaluator(mesh, caster, {1.0f}, {}, GainOptions{}), Error);
}

// The planner with the whole-mesh energy, given candidates around a cube
// seen from one side: the first pick looks at the unseen sides, and the
// second, in the same batch, is not the first's twin.
TEST(Gain, PlannerBatchesCoverTheMesh) {
  Scene scene;
  scene.mesh = gain_test::cube();
  std::vector<float> pri(12, gain_test::kNaN);
  for (const Vec3& eye : {Vec3(0.3, -6, 0.5), Vec3(-0.8, -6, 0.7)}) {
    View v;
    v.label = "existing";
    v.camera = gain_test::looking(eye, Vec3(0, 0, 0));
    v.pixels = std::make_shared<const Image>(640, 480, 1);
    scene.views.push_back(v);
  }
  // The -y face is seen by both views: PRI defined there.
  for (int f : {4, 5}) pri[std::size_t(f)] = 0.1f;
  std::vector<View> given;
  auto add = [&](const std::string& label, const Vec3& eye) {
    View v;
    v.label = label;
    v.camera = gain_test::looking(eye, Vec3(0, 0, 0));
    given.push_back(v);
  };
  add("same_side", Vec3(0.5, -6, 1.0));
  add("east", Vec3(6, -0.3, 0.4));
  add("east_twin", Vec3(6, -0.2, 0.4));
  add("north", Vec3(-0.4, 6, 0.6));
  SuggestOptions o;
  o.mode = CandidateMode::Given;
  o.energy_kind = EnergyKind::Reconstructability;
  o.gain.clusters = 0;
  o.top = 2;
  {
    // With the matchability condition at 45 degrees, east and north see
    // only faces nobody has seen and nothing that matches: no gain. Only
    // the candidate beside the existing views is worth anything.
    o.gain.match_angle = 45;
    const SuggestResult gated = suggest_views(scene, pri, o, given);
    ASSERT_EQ(gated.ranking.size(), 4u);
    for (const auto& c : gated.ranking)
      EXPECT_EQ(c.energy.total > 0, c.label == "same_side") << c.label << " " << c.energy.total;
  }
  // Smith et al.'s pairs alone: the batch goes round the cube.
  o.gain.match_angle = 180;
  const SuggestResult r = suggest_views(scene, pri, o, given);
  ASSERT_EQ(r.suggestions.size(), 2u);
  EXPECT_NE(r.suggestions[0].source, "same_side");
  EXPECT_NE(r.suggestions[1].source, "same_side");
  const bool twins = (r.suggestions[0].source == "east") + (r.suggestions[0].source == "east_twin") +
                         (r.suggestions[1].source == "east") + (r.suggestions[1].source == "east_twin") ==
                     2;
  EXPECT_FALSE(twins) << r.suggestions[0].source << " then " << r.suggestions[1].source;
  EXPECT_TRUE(r.suggestions[0].energy.whole_mesh);
  EXPECT_FALSE(r.suggestions[0].improved_faces.empty());
  // Every given candidate is ranked, with its terms.
  ASSERT_EQ(r.ranking.size(), 4u);
  for (const auto& c : r.ranking) EXPECT_NEAR(c.energy.total, c.energy.refinement + c.energy.exploration, 1e-12);
}

TEST(Hull, CubeHullIsOutwardWithItsArea) {
  std::vector<Vec3> points;
  for (int k = 0; k < 8; ++k) points.push_back(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  points.push_back(Vec3(0.2, -0.1, 0.3));  // inside
  const std::vector<HullTriangle> hull = convex_hull_triangles(points);
  ASSERT_EQ(hull.size(), 12u);
  double area = 0;
  for (const HullTriangle& t : hull) {
    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
    area += 0.5 * n.norm();
    EXPECT_GT(n.dot((t[0] + t[1] + t[2]) / 3), 0.0) << "an inward triangle";
  }
  EXPECT_NEAR(area, 24.0, 1e-12);
  // Coplanar or too few points span no solid.
  EXPECT_TRUE(convex_hull_triangles({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}).empty());
  EXPECT_TRUE(convex_hull_triangles(gain_test::square(4).vertices).empty());
}

// A ground square and a wall along its -y edge, seen from -y: the hull's
// slanted face behind the wall and its sides are surface nobody has seen.
TEST(Gain, UnseenHullStandsForMissingSurface) {
  TriangleMesh mesh = gain_test::square(8);
  const int base = int(mesh.vertices.size());
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) mesh.vertices.push_back(Vec3(-1 + 2.0 * i / 8, -1, 2.0 * j / 8));
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const int a = base + j * 9 + i;  // normal -y
      mesh.faces.push_back({a, a + 1, a + 9 + 1});
      mesh.faces.push_back({a, a + 9 + 1, a + 9});
    }
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  const std::vector<PinholeCamera> existing = {gain_test::looking(Vec3(0, -6, 1), Vec3(0, 0, 0.5))};
  GainOptions o;
  o.clusters = 0;
  const GainEvaluator with(mesh, caster, pri, existing, o);
  o.explore_hull = false;
  const GainEvaluator without(mesh, caster, pri, existing, o);
  EXPECT_EQ(without.num_hull_points(), 0u);
  ASSERT_GT(with.num_hull_points(), 0u);
  EXPECT_EQ(with.num_clusters(), mesh.num_faces() + with.num_hull_points());
  auto hull_gain = [&](const PinholeCamera& c) {
    double sum = 0;
    for (const auto& [k, g] : with.cluster_gains(c))
      if (with.cluster_faces(std::size_t(k)).empty()) sum += g;
    return sum;
  };
  EXPECT_GT(hull_gain(gain_test::looking(Vec3(0, 6, 4), Vec3(0, 0, 0.5))), 0.0);
  // From the side already seen, the hull is the wall itself or faces away.
  EXPECT_EQ(hull_gain(gain_test::looking(Vec3(0.5, -6, 2.5), Vec3(0, 0, 0.5))), 0.0);
}

// The matchability condition (gain.h): one view above the square, a
// candidate whose rays are more than 50 degrees from its rays at every face.
TEST(Gain, RaysBeyondTheMatchAngleGainNothing) {
  const TriangleMesh mesh = gain_test::square(2);
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  const std::vector<PinholeCamera> existing = {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0))};
  const PinholeCamera far = gain_test::looking(Vec3(4 * std::sin(M_PI / 3), 0, 4 * std::cos(M_PI / 3)), Vec3(0, 0, 0));
  const PinholeCamera near = gain_test::looking(Vec3(4 * std::sin(M_PI / 6), 0, 4 * std::cos(M_PI / 6)), Vec3(0, 0, 0));
  GainOptions o;
  o.clusters = 0;
  EXPECT_EQ(o.match_angle, 180.0);  // the default: off
  o.match_angle = 45;
  const GainEvaluator gated(mesh, caster, pri, existing, o);
  o.match_angle = 180;
  const GainEvaluator smith(mesh, caster, pri, existing, o);
  o.match_angle = 70;
  const GainEvaluator wide(mesh, caster, pri, existing, o);
  EXPECT_EQ(gated.evaluate(far).total, 0.0);
  EXPECT_TRUE(gated.cluster_gains(far).empty());
  EXPECT_GT(smith.evaluate(far).total, 0.0);
  EXPECT_DOUBLE_EQ(wide.evaluate(far).total, smith.evaluate(far).total);
  // Within the angle at every face (about 30 degrees): the same as without it.
  EXPECT_GT(gated.evaluate(near).total, 0.0);
  EXPECT_DOUBLE_EQ(gated.evaluate(near).total, smith.evaluate(near).total);
  // The existing views' own reconstructability is not gated.
  EXPECT_EQ(gated.face_reconstructability(), smith.face_reconstructability());
}

// A batch pick is a partner for later picks: alone, a view 80 degrees off
// the existing one's direction matches nothing; after a pick at 60 degrees
// (unmatched itself, so it adds nothing), its rays are 16-26 degrees from
// the pick's.
TEST(Gain, APickIsAPartnerForLaterPicks) {
  const TriangleMesh mesh = gain_test::square(2);
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  GainOptions o;
  o.clusters = 0;
  o.match_angle = 45;
  GainEvaluator gain(mesh, caster, pri, {gain_test::looking(Vec3(0, 0, 4), Vec3(0, 0, 0))}, o);
  auto at = [](double deg) {
    const double a = deg * M_PI / 180;
    return gain_test::looking(Vec3(4 * std::sin(a), 0, 4 * std::cos(a)), Vec3(0, 0, 0));
  };
  EXPECT_EQ(gain.evaluate(at(80)).total, 0.0);
  const std::vector<float> before = gain.face_reconstructability();
  gain.add_view(at(60));
  EXPECT_EQ(gain.face_reconstructability(), before);
  EXPECT_GT(gain.evaluate(at(80)).total, 0.0);
}

// Surface no view sees: a candidate's first-view credit there is scaled by
// the area share of what it sees that matches an existing view. Two equal
// squares, A seen from above, B by nobody; the candidate sees both, A
// within 12-24 degrees of the existing rays: a share of one half.
TEST(Gain, UnseenSurfaceGainsByTheMatchedShare) {
  TriangleMesh mesh = gain_test::square(2);  // A, moved to x in [-3, -1]
  for (Vec3& v : mesh.vertices) v.x() -= 2;
  const TriangleMesh b = gain_test::square(2);  // B, moved to x in [1, 3]
  const int base = int(mesh.vertices.size());
  for (const Vec3& v : b.vertices) mesh.vertices.push_back(v + Vec3(2, 0, 0));
  for (const Face& f : b.faces) mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  const std::size_t half = b.num_faces();
  const RayCaster caster(mesh);
  const std::vector<float> pri(mesh.num_faces(), gain_test::kNaN);
  // Half-fields of 32.6 x 25.6 degrees: from (-2, 0, 4) x reaches 0.56 at most.
  const PinholeCamera e = gain_test::looking(Vec3(-2, 0, 4), Vec3(-2, 0, 0));
  const PinholeCamera c = gain_test::looking(Vec3(0, 0, 6), Vec3(0, 0, 0));
  GainOptions o;
  o.clusters = 0;
  o.explore_hull = false;
  o.target = 100;
  o.match_angle = 45;
  const GainEvaluator gated(mesh, caster, pri, {e}, o);
  o.match_angle = 180;
  const GainEvaluator smith(mesh, caster, pri, {e}, o);
  const std::vector<float> h = gated.face_reconstructability();
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) EXPECT_EQ(h[f] > 0, f < half) << f;
  double dmax_half = 0;
  for (std::size_t f = 0; f < half; ++f) dmax_half = std::max(dmax_half, (e.center() - mesh.face_centroid(f)).norm());
  ASSERT_NEAR(gated.max_distance(), 2 * dmax_half, 1e-12);
  std::map<int, double> g_gated, g_smith;
  for (const auto& [k, g] : gated.cluster_gains(c)) g_gated[k] = g;
  for (const auto& [k, g] : smith.cluster_gains(c)) g_smith[k] = g;
  ASSERT_EQ(g_gated.size(), mesh.num_faces());
  const double total_area = 8.0, gm = gain_test::g_max(), T = 100;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const int k = int(f);  // one cluster per face, in face order
    if (f < half) {
      EXPECT_DOUBLE_EQ(g_gated[k], g_smith[k]) << f;  // matched
      continue;
    }
    const Vec3 p = mesh.face_centroid(f);
    const double cos_theta = (c.center() - p).normalized().z();
    const double s = 1 - (c.center() - p).norm() / gated.max_distance();
    const double dh = 0.5 * (0.5 * gm * cos_theta * s);  // the share times the first-view credit
    const double w = mesh.face_areas()[f] / total_area;  // exploration weight 1
    const double expected = w * (T * T - (T - dh) * (T - dh)) / (T * T);
    EXPECT_NEAR(g_gated[k], expected, 1e-4 * expected) << f;
    EXPECT_LT(g_gated[k], 0.51 * g_smith[k]) << f;
  }
}

// Random points: every point lies inside or on the plane of every hull
// triangle, the triangles close up (each edge met once in each direction),
// V - E + F = 2, and points on a sphere around an interior cloud are
// exactly the hull's vertices.
TEST(Hull, RandomCloudIsClosedConvexAndHasTheSphereAsVertices) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<Vec3> points;
  std::vector<Vec3> sphere;
  for (int i = 0; i < 200; ++i) {
    const Vec3 s = Vec3(g(rng), g(rng), g(rng)).normalized() * 2.0;
    sphere.push_back(s);
    points.push_back(s);
    points.push_back(Vec3(u(rng), u(rng), u(rng)));  // inside
  }
  const std::vector<HullTriangle> hull = convex_hull_triangles(points);
  ASSERT_FALSE(hull.empty());
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edges;
  std::set<std::array<double, 3>> vertices;
  const auto key = [](const Vec3& v) { return std::array<double, 3>{v.x(), v.y(), v.z()}; };
  for (const HullTriangle& t : hull) {
    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    for (const Vec3& p : points) EXPECT_LE(n.dot(p - t[0]), 1e-9);
    for (int k = 0; k < 3; ++k) {
      ++edges[{key(t[k]), key(t[(k + 1) % 3])}];
      vertices.insert(key(t[k]));
    }
  }
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "an open edge";
  }
  const long V = long(vertices.size()), E = long(edges.size()) / 2, F = long(hull.size());
  EXPECT_EQ(V - E + F, 2);
  EXPECT_EQ(vertices.size(), sphere.size());
  for (const Vec3& s : sphere) EXPECT_EQ(vertices.count(key(s)), 1u);
}
