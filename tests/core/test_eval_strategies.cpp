// The baseline strategies of the loop on toy setups with obvious answers.
// Cameras: a ring of 12 around the origin (30 degrees apart) at height 0,
// looking at the origin; a 2 x 2 x 2 box at the origin for coverage.
#include <gtest/gtest.h>

#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/eval/strategies.h"
#include "meshnbv/synth/generators.h"
#include "test_util.h"

namespace meshnbv::eval {
namespace {

PinholeCamera camera_at(const Vec3& eye, const Vec3& target = Vec3::Zero()) {
  return PinholeCamera::look_at(eye, target, Vec3(0, 0, 1), 400, 400, 319.5, 239.5, 640, 480);
}

std::vector<PinholeCamera> ring(int n, double radius, const Vec3& target = Vec3::Zero()) {
  std::vector<PinholeCamera> out;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    out.push_back(camera_at(target + Vec3(radius * std::cos(a), radius * std::sin(a), 1.0), target));
  }
  return out;
}

TEST(EvalStrategies, ConvergencePointOfARing) {
  const Vec3 target(1, 2, 3);
  const Vec3 c = convergence_point(ring(12, 5, target));
  EXPECT_NEAR((c - target).norm(), 0.0, 1e-9);
}

TEST(EvalStrategies, UniformFillsTheLargestGap) {
  const auto cams = ring(12, 5);
  std::vector<PinholeCamera> candidates(cams.begin() + 1, cams.end());  // views 1..11
  // Selected: view 0 at 0 degrees -> the opposite view (180 degrees = view 6 = candidate 5).
  EXPECT_EQ(pick_uniform({cams[0]}, candidates, Vec3::Zero()), 5);
  // Selected 0 and 180 degrees -> 90 degrees (view 3 = candidate 2) before 270.
  EXPECT_EQ(pick_uniform({cams[0], cams[6]}, candidates, Vec3::Zero()), 2);
  EXPECT_EQ(pick_uniform({cams[0]}, {}, Vec3::Zero()), -1);
}

TEST(EvalStrategies, CoveragePrefersUnseenFaces) {
  const TriangleMesh box = synth::make_box(Vec3(-1, -1, -1), Vec3(1, 1, 1), 0.5, 0);
  // Two selected views see the +x side (and a bit of the top).
  const std::vector<PinholeCamera> selected{camera_at(Vec3(6, 0.5, 0.5)), camera_at(Vec3(6, -0.5, 0.5))};
  const std::vector<PinholeCamera> candidates{
      camera_at(Vec3(6, 0, 0.2)),   // +x again: nothing new
      camera_at(Vec3(5, 5, 0.2)),   // +x (covered) and +y
      camera_at(Vec3(-4, -4, 4)),   // -x, -y and the top
  };
  std::vector<int> counts;
  EXPECT_EQ(pick_coverage(box, selected, candidates, 2, &counts), 2);
  ASSERT_EQ(counts.size(), 3u);
  EXPECT_EQ(counts[0], 0);
  EXPECT_GT(counts[1], 0);
  EXPECT_GT(counts[2], counts[1]);
  // With one view enough to count as covered, the top seen by the selected
  // views is covered too; the answer stays.
  EXPECT_EQ(pick_coverage(box, selected, candidates, 1), 2);
  // An empty mesh: nothing to cover, the first candidate.
  EXPECT_EQ(pick_coverage(TriangleMesh{}, selected, candidates), 0);
}

TEST(EvalStrategies, RandomIsSeededAndInRange) {
  std::mt19937_64 a(5), b(5);
  for (int k = 0; k < 20; ++k) {
    const int x = pick_random(7, a);
    EXPECT_EQ(x, pick_random(7, b));
    EXPECT_GE(x, 0);
    EXPECT_LT(x, 7);
  }
  EXPECT_EQ(pick_random(0, a), -1);
}

TEST(EvalStrategies, Names) {
  for (const char* n : {"nbv", "uniform", "random", "coverage"})
    EXPECT_EQ(strategy_name(parse_strategy(n)), n);
  MESHNBV_EXPECT_ERROR_CONTAINS(parse_strategy("best"), "unknown strategy 'best'");
}

}  // namespace
}  // namespace meshnbv::eval
