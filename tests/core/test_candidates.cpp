// Candidate poses (SPEC section 5) against geometry known in closed form:
// SafetyChecker::inside_volume on boxes and planes, the Fibonacci sampling
// on the hemisphere, and refine_candidate on scenes whose optimum is known.
// Every expected value is computed here, independently of the core
// (tests/core/test_geometry.h for distances and insideness).
#include <algorithm>
#include <array>
#include <iostream>
#include <memory>
#include <cmath>
#include <vector>

#include "meshnbv/candidates.h"
#include "meshnbv/error.h"
#include "meshnbv/synth/generators.h"
#include "test_geometry.h"
#include "test_util.h"

using namespace meshnbv;
using test::kDeg;

namespace {


// fn(p) for the points of a lattice of spacing 0.1 starting at `from` and
// below `to`; the starts used here keep every point off the boxes' face
// planes (which lie on multiples of 0.5).
template <class F>
void for_lattice(const Vec3& from, const Vec3& to, F fn) {
  for (double x = from.x(); x < to.x(); x += 0.1)
    for (double y = from.y(); y < to.y(); y += 0.1)
      for (double z = from.z(); z < to.z(); z += 0.1) fn(Vec3(x, y, z));
}

PinholeCamera intrinsics() { return test::centred_camera(500, 640, 480); }

// A region given by its centroid and normal only (all that the sampling uses).
WorstRegion region_at(const Vec3& centroid, const Vec3& normal) {
  WorstRegion r;
  r.centroid = centroid;
  r.mean_normal = normal.normalized();
  return r;
}

// Angle of v about the axis n, measured in the plane orthogonal to n from
// an arbitrary fixed reference (only differences are used).
double azimuth(const Vec3& v, const Vec3& n) {
  const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = n.cross(a).normalized(), e2 = n.cross(e1);
  return std::atan2(v.dot(e2), v.dot(e1));
}

double wrap(double a) { return std::remainder(a, 2 * M_PI); }

const Vec3 kBoxLo(-1.0, -0.5, 0.0), kBoxHi(1.0, 0.5, 2.0);

}  // namespace

// --- SafetyChecker::inside_volume -----------------------------------------

TEST(InsideVolume, ClosedBoxMatchesTheIntervalTest) {
  const TriangleMesh box = synth::make_box(kBoxLo, kBoxHi, 0.5, 0);
  const RayCaster caster(box);
  const SafetyChecker safety(box, caster, 0.0);
  int inside = 0, outside = 0;
  // A lattice of points in and around the box, off its face planes.
  for_lattice(Vec3(-1.45, -0.95, -0.45), Vec3(1.5, 1.0, 2.5), [&](const Vec3& p) {
    const bool expected = test::in_box(p, kBoxLo, kBoxHi);
    EXPECT_EQ(safety.inside_volume(p), expected) << p.transpose();
    (expected ? inside : outside)++;
    // The interval test agrees with the winding number of the mesh.
    EXPECT_NEAR(test::winding_number(box, p), expected ? 1 : 0, 1e-9) << p.transpose();
  });
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

TEST(InsideVolume, UnderAnOpenGroundPlaneIsInside) {
  // A bounded plane z = 0 facing +z: below it (seen from its back) counts
  // as inside the solid it bounds, above it as outside.
  const TriangleMesh ground = synth::make_ground(Vec3(-50, -50, 0), Vec3(50, 50, 0), 5.0, 0);
  const RayCaster caster(ground);
  const SafetyChecker safety(ground, caster, 0.0);
  for (const Vec3& xy : {Vec3(0, 0, 0), Vec3(3.3, -7.1, 0), Vec3(-12.5, 20.2, 0)})
    for (double z : {1e-3, 0.5, 10.0}) {
      EXPECT_TRUE(safety.inside_volume(xy - Vec3(0, 0, z))) << (xy - Vec3(0, 0, z)).transpose();
      EXPECT_FALSE(safety.inside_volume(xy + Vec3(0, 0, z))) << (xy + Vec3(0, 0, z)).transpose();
    }
}

// A union of the box and a second closed box: every lattice point in and
// around them against the interval tests. Returns the counts (in the first,
// in the second, in both).
std::array<int, 3> check_union(const Vec3& lo2, const Vec3& hi2) {
  TriangleMesh two = synth::make_box(kBoxLo, kBoxHi, 0.5, 0);
  two.append(synth::make_box(lo2, hi2, 0.5, 0));
  const RayCaster caster(two);
  const SafetyChecker safety(two, caster, 0.0);
  std::array<int, 3> counts{};
  for_lattice(Vec3(-1.45, -0.95, -0.45), Vec3(3.5, 2.0, 2.5), [&](const Vec3& p) {
    const bool a = test::in_box(p, kBoxLo, kBoxHi), b = test::in_box(p, lo2, hi2);
    EXPECT_EQ(safety.inside_volume(p), a || b) << p.transpose();
    counts[0] += a;
    counts[1] += b;
    counts[2] += a && b;
  });
  return counts;
}

TEST(InsideVolume, UnionOfTwoDisjointClosedBoxes) {
  const auto counts = check_union(Vec3(2.0, -0.5, 0.0), Vec3(3.0, 1.5, 1.0));
  EXPECT_GT(counts[0], 500);
  EXPECT_GT(counts[1], 500);
  EXPECT_EQ(counts[2], 0);
}

// Overlapping components (a second box through the first one's +x wall):
// the first hit alone would read points inside one box near a face of the
// other as outside (108 lattice points before the winding rule); the signed
// crossings count them right.
TEST(InsideVolume, UnionOfTwoOverlappingClosedBoxes) {
  const auto counts = check_union(Vec3(0.5, -0.3, 0.5), Vec3(2.0, 0.3, 1.5));
  EXPECT_GT(counts[2], 50);  // points inside both
  EXPECT_GT(counts[1] - counts[2], 50);  // inside the second only
}

TEST(InsideVolume, PointsExactlyOnAFace) {
  // On the surface inside_volume is unspecified (the rays start on a face;
  // which way they count depends on their direction): such a point is
  // unsafe because it is too close, for any positive safety distance.
  // A hair off the face, either side, follows the interval test.
  const TriangleMesh box = synth::make_box(kBoxLo, kBoxHi, 0.5, 0);
  const RayCaster caster(box);
  const SafetyChecker safety(box, caster, 1e-9);
  const std::vector<std::pair<Vec3, Vec3>> on_face = {  // point, outward normal
      {Vec3(0.1, 0.2, 2.0), Vec3::UnitZ()},  {Vec3(0.1, 0.2, 0.0), -Vec3::UnitZ()},
      {Vec3(1.0, 0.1, 0.7), Vec3::UnitX()},  {Vec3(-1.0, -0.3, 1.3), -Vec3::UnitX()},
      {Vec3(0.3, 0.5, 0.9), Vec3::UnitY()},  {Vec3(-0.6, -0.5, 0.1), -Vec3::UnitY()},
      {Vec3(0.5, 0.25, 2.0), Vec3::UnitZ()},  // on a mesh vertex (edge 0.5 grid)
      {Vec3(0.25, 0.5, 1.0), Vec3::UnitY()}};  // on a mesh edge
  for (const auto& [p, n] : on_face) {
    EXPECT_NEAR(safety.distance_to_surface(p), 0.0, 1e-12) << p.transpose();
    EXPECT_NEAR(test::box_surface_distance(p, kBoxLo, kBoxHi), 0.0, 1e-15);
    EXPECT_TRUE(safety.too_close(p)) << p.transpose();
    EXPECT_FALSE(safety.safe(p)) << p.transpose();
    const Vec3 out = p + 1e-4 * n, in = p - 1e-4 * n;
    ASSERT_FALSE(test::in_box(out, kBoxLo, kBoxHi));
    ASSERT_TRUE(test::in_box(in, kBoxLo, kBoxHi));
    EXPECT_FALSE(safety.inside_volume(out)) << out.transpose();
    EXPECT_TRUE(safety.inside_volume(in)) << in.transpose();
  }
}

// --- sample_candidates ----------------------------------------------------

namespace {

// Sampling far from any surface: a tiny triangle 1 km below, safety
// distance 0, so that nothing is rejected.
struct OpenSpace {
  TriangleMesh mesh = synth::make_ground(Vec3(0, 0, -1000), Vec3(1, 1, -1000), 1.0, 0);
  RayCaster caster{mesh};
  SafetyChecker safety{mesh, caster, 0.0};
};

const Vec3 kNormal = Vec3(0.3, -0.2, 0.9).normalized();
const Vec3 kCentroid(1.0, 2.0, 3.0);

}  // namespace

TEST(SampleCandidates, CountOnTheOpenHemisphere) {
  const OpenSpace space;
  SamplingOptions o;
  o.directions = 100;
  const WorstRegion region = region_at(kCentroid, kNormal);
  const CandidateSet set = sample_candidates(region, intrinsics(), Vec3::UnitZ(), 4.0, space.safety, o);
  EXPECT_EQ(set.generated, 300u);  // 100 directions x 3 distances
  EXPECT_EQ(set.cameras.size(), 300u);
  EXPECT_EQ(set.rejected_inside + set.rejected_too_close, 0u);
  // Direction k at height 1 - (k + 1/2) / N over the region's normal
  // (evenly spaced in (0, 1): equal areas on the open hemisphere).
  for (std::size_t i = 0; i < set.cameras.size(); ++i) {
    const int k = int(i / 3);
    const Vec3 d = (set.cameras[i].center() - kCentroid).normalized();
    EXPECT_NEAR(d.dot(kNormal), 1.0 - (k + 0.5) / 100.0, 1e-12) << i;
    EXPECT_GT(d.dot(kNormal), 0.0);
  }
}

TEST(SampleCandidates, AllLookAtTheCentroidWithTheGivenUp) {
  const OpenSpace space;
  SamplingOptions o;
  o.directions = 64;
  const Vec3 up = Vec3(0.1, 0.0, 1.0).normalized();
  const PinholeCamera intr = intrinsics();
  const CandidateSet set =
      sample_candidates(region_at(kCentroid, kNormal), intr, up, 4.0, space.safety, o);
  ASSERT_EQ(set.cameras.size(), 192u);
  for (const PinholeCamera& c : set.cameras) {
    const Vec3 to_centroid = (kCentroid - c.center()).normalized();
    EXPECT_GT(c.forward().dot(to_centroid), 1.0 - 1e-12);
    Vec2 px;
    ASSERT_TRUE(c.project(kCentroid, &px));
    EXPECT_NEAR(px.x(), intr.cx, 1e-6);
    EXPECT_NEAR(px.y(), intr.cy, 1e-6);
    EXPECT_EQ(c.fx, intr.fx);
    EXPECT_EQ(c.width, intr.width);
    // Image up (-down) in the plane of `up` and the viewing direction, on
    // the side of `up`: no roll.
    EXPECT_NEAR(c.right().dot(up), 0.0, 1e-12);
    EXPECT_GT(-c.down().dot(up), 0.0);
  }
}

TEST(SampleCandidates, DistancesAreTheFactorsTimesTheViewingDistance) {
  const OpenSpace space;
  SamplingOptions o;
  o.directions = 50;
  o.distance_factors = {0.5, 1.25, 2.0, 3.0};
  const double d = 7.5;
  const CandidateSet set =
      sample_candidates(region_at(kCentroid, kNormal), intrinsics(), Vec3::UnitZ(), d, space.safety, o);
  ASSERT_EQ(set.cameras.size(), 200u);
  for (std::size_t i = 0; i < set.cameras.size(); ++i) {
    const double expected = o.distance_factors[i % 4] * d;
    EXPECT_NEAR((set.cameras[i].center() - kCentroid).norm(), expected, 1e-12 * expected) << i;
    // The four distances of one direction lie on one ray from the centroid.
    const Vec3 dir0 = (set.cameras[i - i % 4].center() - kCentroid).normalized();
    EXPECT_GT((set.cameras[i].center() - kCentroid).normalized().dot(dir0), 1.0 - 1e-12);
  }
}

TEST(SampleCandidates, FibonacciSpiralAndTheSeedRotatesIt) {
  const OpenSpace space;
  SamplingOptions o;
  o.directions = 40;
  o.distance_factors = {1.0};
  const WorstRegion region = region_at(kCentroid, kNormal);
  auto azimuths = [&](std::uint64_t seed) {
    o.seed = seed;
    const CandidateSet set = sample_candidates(region, intrinsics(), Vec3::UnitZ(), 3.0, space.safety, o);
    std::vector<double> a;
    for (const auto& c : set.cameras) a.push_back(azimuth(c.center() - kCentroid, kNormal));
    return a;
  };
  const std::vector<double> a = azimuths(1), b = azimuths(2), a_again = azimuths(1);
  ASSERT_EQ(a.size(), 40u);
  ASSERT_EQ(b.size(), 40u);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));  // 137.5 degrees
  for (std::size_t k = 1; k < a.size(); ++k) {
    EXPECT_NEAR(wrap(a[k] - a[k - 1] - golden), 0.0, 1e-9) << k;
    EXPECT_NEAR(wrap(b[k] - b[k - 1] - golden), 0.0, 1e-9) << k;
  }
  // Another seed turns the whole spiral by one angle about the normal.
  const double turn = wrap(b[0] - a[0]);
  EXPECT_GT(std::abs(turn), 1e-3);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(wrap(b[k] - a[k] - turn), 0.0, 1e-9) << k;
    EXPECT_EQ(a[k], a_again[k]);  // the same seed, the same poses
  }
}

TEST(SampleCandidates, RejectedCountsAddUpAndMatchTheGeometry) {
  // The region: the centre of a 20 m ground plane. A closed box floats over
  // it on one side, 1-3 m up; poses inside the box or nearer than 0.4 m to
  // any surface are rejected. The expected tally is made here with the
  // brute-force distance and the box's interval test, on the poses the
  // same spiral gives in open space.
  const Vec3 lo(0.5, -1.5, 1.0), hi(2.5, 1.5, 3.0);
  TriangleMesh scene = synth::make_ground(Vec3(-10, -10, 0), Vec3(10, 10, 0), 2.0, 0);
  scene.append(synth::make_box(lo, hi, 0.5, 0));
  const RayCaster caster(scene);
  const double safety_distance = 0.4;
  const SafetyChecker safety(scene, caster, safety_distance);
  SamplingOptions o;
  o.directions = 200;
  o.distance_factors = {0.1, 1.0, 1.5};
  const WorstRegion region = region_at(Vec3(0, 0, 0), Vec3::UnitZ());
  const double d = 2.0;
  const CandidateSet set = sample_candidates(region, intrinsics(), Vec3::UnitY(), d, safety, o);
  // Every generated pose, from the same call in open space.
  TriangleMesh far = synth::make_ground(Vec3(0, 0, -1000), Vec3(1, 1, -1000), 1.0, 0);
  const RayCaster far_caster(far);
  const CandidateSet all =
      sample_candidates(region, intrinsics(), Vec3::UnitY(), d, SafetyChecker(far, far_caster, 0.0), o);
  ASSERT_EQ(all.cameras.size(), 600u);
  std::size_t too_close = 0, inside = 0;
  std::vector<Vec3> kept;
  for (const auto& c : all.cameras) {
    const Vec3 p = c.center();
    const double dist = test::brute_force_distance(scene, p);
    ASSERT_GT(std::abs(dist - safety_distance), 1e-4) << "a pose on the rule's boundary";
    if (dist < safety_distance) ++too_close;  // checked first, as the SPEC lists it
    else if (test::in_box(p, lo, hi)) ++inside;
    else kept.push_back(p);
  }
  EXPECT_EQ(set.generated, 600u);
  EXPECT_EQ(set.rejected_too_close, too_close);
  EXPECT_EQ(set.rejected_inside, inside);
  EXPECT_EQ(set.cameras.size() + set.rejected_inside + set.rejected_too_close, set.generated);
  ASSERT_EQ(set.cameras.size(), kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i)
    EXPECT_NEAR((set.cameras[i].center() - kept[i]).norm(), 0.0, 1e-12);
  // The scene exercises both rules.
  EXPECT_GT(too_close, 100u);  // the 0.2 m ring of poses is near the ground
  EXPECT_GT(inside, 5u);
}

// --- refine_candidate -----------------------------------------------------

namespace {

// A 0.2 m square at the origin facing +z, all of it the worst region (4
// vertices, normal +z), no existing view (no parallax term). For a pose at
// incidence x looking at the square, every vertex scores about
// 0.6 O + 1.6 F + 0.6 I(x) with O = 1 and F ~ 0, so E <= 4 (0.6 + 0.6 I(mu))
// (F <= 0 and I <= I(mu) everywhere), reached at 55 degrees from the
// normal, looking at the centroid, at any distance and azimuth.
struct SmallSquare {
  TriangleMesh mesh;
  std::unique_ptr<RayCaster> caster;
  WorstRegion region;
  EnergyOptions options;
  explicit SmallSquare(const TriangleMesh& extra = {}) {
    mesh = synth::make_ground(Vec3(-0.1, -0.1, 0), Vec3(0.1, 0.1, 0), 0.2, 0);
    const std::size_t square_faces = mesh.num_faces();
    if (!extra.empty()) mesh.append(extra);
    caster = std::make_unique<RayCaster>(mesh);
    std::vector<float> pri(mesh.num_faces(), 0.0f);
    std::fill(pri.begin(), pri.begin() + long(square_faces), 1.0f);
    region = worst_region(mesh, pri, int(square_faces));
  }
  double upper_bound() const { return 4 * (0.6 + 0.6 * incidence_term(55 * kDeg, options)); }
};

// A camera at `distance` from the origin, `incidence` degrees from +z in
// the xz-plane, turned `off` degrees (about +z) away from the origin.
PinholeCamera pose_at(double incidence, double distance, double off) {
  const Vec3 c = distance * Vec3(std::sin(incidence * kDeg), 0, std::cos(incidence * kDeg));
  const Vec3 to = -c.normalized();
  const Vec3 dir = Eigen::AngleAxisd(off * kDeg, Vec3::UnitZ()) * to;
  return camera_looking(intrinsics(), c, dir, Vec3::UnitZ());
}

double incidence_deg(const PinholeCamera& c) {
  return std::acos(c.center().normalized().z()) / kDeg;
}
double pointing_error_deg(const PinholeCamera& c) {
  return std::acos(std::clamp(c.forward().dot(-c.center().normalized()), -1.0, 1.0)) / kDeg;
}

}  // namespace

TEST(RefineCandidate, MovesTowardsTheKnownOptimumAndStrictlyImproves) {
  const SmallSquare s;
  const EnergyEvaluator e(s.mesh, *s.caster, s.region, {}, s.options);
  const SafetyChecker safety(s.mesh, *s.caster, 0.05 * s.mesh.bounding_box().diagonal());
  const PinholeCamera start = pose_at(25, 5.0, 10);
  ASSERT_TRUE(safety.safe(start.center()));
  const double e0 = e.evaluate(start).total, bound = s.upper_bound();
  const PinholeCamera refined = refine_candidate(start, Vec3::UnitZ(), e, safety);
  const double e1 = e.evaluate(refined).total;
  std::cout << "start: incidence " << incidence_deg(start) << " pointing " << pointing_error_deg(start)
            << " E " << e0 << "; refined: incidence " << incidence_deg(refined) << " pointing "
            << pointing_error_deg(refined) << " E " << e1 << "; bound " << bound << "\n";
  EXPECT_GT(e1, e0 + 1.0);
  EXPECT_LE(e1, bound + 1e-12);
  EXPECT_GT(e1, bound - 0.05);
  EXPECT_LT(std::abs(incidence_deg(refined) - 55), 2.0);
  EXPECT_LT(pointing_error_deg(refined), 1.0);
}

TEST(RefineCandidate, NeverReturnsAnUnsafePose) {
  // The same square with a closed wall x in [3, 10] next to it. From 25
  // degrees on the wall's side, the optimum at the same distance (x = 4.1)
  // is inside the wall; with a 0.5 m safety distance the safe poses have
  // x <= 2.5. Checked with the brute-force distance and the wall's interval
  // test, for several starts and iteration budgets.
  const Vec3 lo(3, -10, -1), hi(10, 10, 10);
  const SmallSquare walled(synth::make_box(lo, hi, 1.0, 0));
  const SmallSquare open;
  const double margin = 0.5;
  const EnergyEvaluator e(walled.mesh, *walled.caster, walled.region, {}, walled.options);
  const SafetyChecker safety(walled.mesh, *walled.caster, margin);
  const EnergyEvaluator e_open(open.mesh, *open.caster, open.region, {}, open.options);
  const SafetyChecker safety_open(open.mesh, *open.caster, 0.0);
  int crossings = 0;
  for (double incidence : {15.0, 25.0, 30.0})
    for (double distance : {4.0, 5.0})
      for (int iterations : {20, 150, 400}) {
        const PinholeCamera start = pose_at(incidence, distance, 3);
        ASSERT_GT(test::brute_force_distance(walled.mesh, start.center()), margin);
        RefineOptions o;
        o.iterations = iterations;
        o.position_step = 0.3;  // a simplex that reaches across the rule's boundary
        const PinholeCamera r = refine_candidate(start, Vec3::UnitZ(), e, safety, o);
        const Vec3 c = r.center();
        // Most results lie on the rule's boundary (x = 2.5): 1e-6 m of slack
        // for the checker's own rounding.
        EXPECT_GE(test::brute_force_distance(walled.mesh, c), margin - 1e-6) << c.transpose();
        EXPECT_FALSE(test::in_box(c, lo, hi)) << c.transpose();
        EXPECT_GE(e.evaluate(r).total, e.evaluate(start).total);
        // Without the wall the same refinement goes where the wall is: the
        // rule binds in this scene.
        const PinholeCamera free = refine_candidate(start, Vec3::UnitZ(), e_open, safety_open, o);
        crossings += free.center().x() > lo.x() - margin;
      }
  // Measured: 10 of the 18.
  EXPECT_GT(crossings, 6) << "of 18 unconstrained refinements ended where the walled scene is unsafe";
}

TEST(RefineCandidate, RespectsIterationsAndCountsItsEvaluations) {
  const SmallSquare s;
  const EnergyEvaluator e(s.mesh, *s.caster, s.region, {}, s.options);
  const SafetyChecker safety(s.mesh, *s.caster, 0.0);  // every probed pose is feasible
  const PinholeCamera start = pose_at(25, 5.0, 10);
  std::size_t previous = 0;
  double previous_energy = -std::numeric_limits<double>::infinity();
  for (int iterations = 0; iterations <= 40; ++iterations) {
    RefineOptions o;
    o.iterations = iterations;
    std::size_t reported = 0;
    const std::size_t before = e.evaluations();
    const PinholeCamera r = refine_candidate(start, Vec3::UnitZ(), e, safety, o, &reported);
    // The evaluator's own count of evaluate() calls.
    EXPECT_EQ(reported, e.evaluations() - before) << iterations;
    // Nelder-Mead: the 6 simplex vertices, then per iteration a reflection
    // and at most an expansion or a contraction, or a contraction and a
    // shrink of 5 vertices.
    if (iterations == 0) {
      EXPECT_EQ(reported, 6u);
    } else {
      EXPECT_GE(reported, previous + 1) << iterations;
      EXPECT_LE(reported, previous + 7) << iterations;
    }
    // Each run repeats the previous one and goes one iteration further:
    // the best pose can only get better.
    const double energy = e.evaluate(r).total;
    EXPECT_GE(energy, previous_energy) << iterations;
    previous = reported;
    previous_energy = energy;
  }
}

// --- the ground (above_ground) ------------------------------------------------

namespace {

// A ring camera at azimuth `az` (degrees) around the origin, `elevation`
// degrees above it, looking at the origin, no roll about world +z.
PinholeCamera ring_camera(double az, double elevation, double distance) {
  const double e = elevation * kDeg, a = az * kDeg;
  const Vec3 c = distance * Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
  return camera_looking(intrinsics(), c, -c, Vec3::UnitZ());
}

}  // namespace

TEST(LevelUp, ThreeRingViewsLookingDownGiveTheWorldUpWhereTheMeanUpTilts) {
  // Three neighbours of a ring 25 degrees up, looking down at its centre:
  // each image-up leans 25 degrees towards the centre, so their mean leans
  // too (by about 25 degrees); their right axes are horizontal, and the
  // direction perpendicular to all of them is +z.
  const std::vector<PinholeCamera> cams = {ring_camera(-15, 25, 20), ring_camera(0, 25, 20),
                                           ring_camera(15, 25, 20)};
  const double mean_tilt = std::acos(mean_up(cams).dot(Vec3::UnitZ())) / kDeg;
  EXPECT_GT(mean_tilt, 20.0);
  EXPECT_NEAR(level_up(cams).dot(Vec3::UnitZ()), 1.0, 1e-12);
  // Upside down (every camera rolled 180 degrees) the sign follows them.
  std::vector<PinholeCamera> flipped;
  for (const auto& c : cams)
    flipped.push_back(camera_looking(intrinsics(), c.center(), c.forward(), -Vec3::UnitZ()));
  EXPECT_NEAR(level_up(flipped).dot(-Vec3::UnitZ()), 1.0, 1e-12);
}

TEST(LevelUp, ParallelRightAxesFallBackToTheMeanUp) {
  // One camera, or two on one line of sight: the right axes span one
  // direction only, and the image up is all there is.
  const PinholeCamera one = ring_camera(30, 25, 20);
  EXPECT_NEAR(level_up({one}).dot(-one.down()), 1.0, 1e-12);
  const PinholeCamera nearer = ring_camera(30, 25, 10);
  EXPECT_NEAR(level_up({one, nearer}).dot(-one.down()), 1.0, 1e-12);
}

TEST(GroundHeight, FirstPercentileOfTheHeightsIgnoresAStrayVertex) {
  // A 2 m box standing on z = 1 (vertices at heights 1 and 3 only) plus one
  // stray vertex far below: the 1st percentile is still the box's base.
  TriangleMesh box = synth::make_box(Vec3(0, 0, 1), Vec3(2, 2, 3), 0.25, 0);
  const double lowest = 1.0;
  EXPECT_NEAR(ground_height(box, Vec3::UnitZ()), lowest, 1e-12);
  box.vertices.push_back(Vec3(1, 1, -50));
  ASSERT_GT(box.vertices.size(), 100u);  // one vertex is less than 1%
  EXPECT_NEAR(ground_height(box, Vec3::UnitZ()), lowest, 1e-12);
  // Along -z the "ground" is the box's top (heights -3).
  EXPECT_NEAR(ground_height(box, -Vec3::UnitZ()), -3.0, 1e-12);
  EXPECT_THROW(ground_height(TriangleMesh{}, Vec3::UnitZ()), Error);
}

TEST(SampleCandidates, NoPoseBelowTheGroundAndTheCountsAddUp) {
  // A wall's region (normal +x) at height 2: its hemisphere reaches 4 m
  // below and above. With the ground at height 1 every kept pose is at
  // least that high, those below are counted, and the rest are the poses
  // the same spiral gives without a ground, in order.
  const OpenSpace space;
  SafetyChecker grounded(space.mesh, space.caster, 0.0);
  grounded.set_ground(Vec3::UnitZ(), 1.0);
  SamplingOptions o;
  o.directions = 200;
  const WorstRegion region = region_at(Vec3(0, 0, 2), Vec3::UnitX());
  const CandidateSet all = sample_candidates(region, intrinsics(), Vec3::UnitZ(), 4.0, space.safety, o);
  const CandidateSet set = sample_candidates(region, intrinsics(), Vec3::UnitZ(), 4.0, grounded, o);
  std::vector<Vec3> expected;
  for (const auto& c : all.cameras)
    if (c.center().z() >= 1.0) expected.push_back(c.center());
  EXPECT_EQ(set.generated, 600u);
  EXPECT_EQ(set.rejected_below_ground, all.cameras.size() - expected.size());
  EXPECT_GT(set.rejected_below_ground, 150u);  // the spiral's lower half, about
  EXPECT_EQ(set.cameras.size() + set.rejected_below_ground + set.rejected_inside + set.rejected_too_close,
            set.generated);
  ASSERT_EQ(set.cameras.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(set.cameras[i].center(), expected[i]) << i;
  EXPECT_FALSE(grounded.safe(Vec3(0, 0, 0.999)));
  EXPECT_TRUE(grounded.safe(Vec3(0, 0, 1.001)));
  EXPECT_THROW(grounded.set_ground(Vec3(0, 0, 2), 1.0), Error);  // not a unit vector
}
