// Repeated loops: starting sets spread over a ring, the Student t critical
// values against their closed forms, mean and interval by hand, the
// per-view-count summary of hand-made runs.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "meshnbv/error.h"
#include "meshnbv/eval/experiment.h"

namespace meshnbv::eval {
namespace {

// A ring of n views around the origin, view k at 360 k / n degrees.
std::vector<View> ring_views(int n) {
  std::vector<View> out;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    View v;
    v.label = "view" + std::to_string(k);
    v.camera = PinholeCamera::look_at(Vec3(5 * std::cos(a), 5 * std::sin(a), 1.0), Vec3::Zero(), Vec3(0, 0, 1),
                                      400, 400, 319.5, 239.5, 640, 480);
    out.push_back(v);
  }
  return out;
}

TEST(EvalExperiment, BootstrapsSpreadOverARing) {
  const auto views = ring_views(12);
  // Centres: view 0, the opposite view 6, then 3 (90 degrees; 9 ties with
  // it and has the higher index), then 9; each with its two neighbours.
  const auto sets = spread_bootstraps(views, 4, 3);
  ASSERT_EQ(sets.size(), 4u);
  EXPECT_EQ(sets[0], (std::vector<int>{0, 1, 11}));
  EXPECT_EQ(sets[1], (std::vector<int>{5, 6, 7}));
  EXPECT_EQ(sets[2], (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(sets[3], (std::vector<int>{8, 9, 10}));
  // One set: the loop's default bootstrap, view 0 and its nearest views.
  EXPECT_EQ(spread_bootstraps(views, 1, 3), (std::vector<std::vector<int>>{{0, 1, 11}}));
  // Every view a centre: all distinct centres.
  const auto all = spread_bootstraps(views, 12, 2);
  std::set<std::vector<int>> distinct(all.begin(), all.end());
  EXPECT_EQ(all.size(), 12u);
  EXPECT_GE(distinct.size(), 6u);  // each pair {k, neighbour} can come twice at most
}

TEST(EvalExperiment, BootstrapsOutOfRange) {
  const auto views = ring_views(5);
  EXPECT_THROW(spread_bootstraps(views, 0, 3), Error);
  EXPECT_THROW(spread_bootstraps(views, 6, 3), Error);
  EXPECT_THROW(spread_bootstraps(views, 2, 6), Error);
  EXPECT_THROW(spread_bootstraps(views, 2, 0), Error);
  EXPECT_THROW(spread_bootstraps({}, 1, 1), Error);
}

TEST(EvalExperiment, StudentTCriticalValuesHaveTheirClosedForms) {
  // One degree of freedom: the Cauchy distribution, t = tan(pi (p - 1/2)).
  EXPECT_NEAR(student_t_critical(1, 0.95), std::tan(M_PI * 0.475), 1e-9);
  EXPECT_NEAR(student_t_critical(1, 0.5), 1.0, 1e-12);
  // Two: t = (2p - 1) / sqrt(2 p (1 - p)), p = 0.975.
  const double p = 0.975;
  EXPECT_NEAR(student_t_critical(2, 0.95), (2 * p - 1) / std::sqrt(2 * p * (1 - p)), 1e-9);
  // Many: the normal quantile, sqrt(2) erfinv(0.95) = 1.959963985...
  EXPECT_NEAR(student_t_critical(1000000, 0.95), 1.959963985, 1e-5);
  // Falls with the degrees of freedom.
  EXPECT_GT(student_t_critical(4), student_t_critical(5));
  EXPECT_THROW(student_t_critical(0), Error);
  EXPECT_THROW(student_t_critical(3, 1.0), Error);
  EXPECT_THROW(student_t_critical(3, 0.0), Error);
}

TEST(EvalExperiment, MeanIntervalByHand) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // 1..5 (and a NaN left out): mean 3, s = sqrt(2.5), half-width t(4) s / sqrt(5).
  const MeanInterval m = mean_interval({1, 2, nan, 3, 4, 5});
  EXPECT_EQ(m.n, 5u);
  EXPECT_DOUBLE_EQ(m.mean, 3.0);
  const double half = student_t_critical(4) * std::sqrt(2.5) / std::sqrt(5.0);
  EXPECT_NEAR(m.low, 3.0 - half, 1e-12);
  EXPECT_NEAR(m.high, 3.0 + half, 1e-12);
  EXPECT_NEAR(half, 1.963243, 1e-6);  // 2.776445 * 1.581139 / 2.236068
  EXPECT_EQ(m.min, 1.0);
  EXPECT_EQ(m.max, 5.0);
  // Equal values: zero width.
  const MeanInterval same = mean_interval({0.25, 0.25, 0.25});
  EXPECT_EQ(same.low, 0.25);
  EXPECT_EQ(same.high, 0.25);
  // One value: its own (no spread known).
  const MeanInterval one = mean_interval({7});
  EXPECT_EQ(one.n, 1u);
  EXPECT_EQ(one.low, 7.0);
  EXPECT_EQ(one.high, 7.0);
  // None finite: NaN everywhere.
  const MeanInterval none = mean_interval({nan, std::numeric_limits<double>::infinity()});
  EXPECT_EQ(none.n, 0u);
  EXPECT_TRUE(std::isnan(none.mean) && std::isnan(none.low) && std::isnan(none.high));
}

// A run whose step k has 3 + k views, completeness c[k] at threshold 0.01
// and 90% accuracy a[k].
LoopResult run_of(const std::vector<double>& c, const std::vector<double>& a) {
  LoopResult r;
  for (std::size_t k = 0; k < c.size(); ++k) {
    StepRecord s;
    s.step = int(k);
    for (std::size_t v = 0; v < 3 + k; ++v) s.views.push_back("v" + std::to_string(v));
    s.faces = 100 * (k + 1);
    s.metrics.accuracy = {{90.0, a[k]}};
    s.metrics.completeness = {{0.01, c[k]}};
    s.metrics.mean_accuracy = a[k] / 2;
    r.steps.push_back(s);
  }
  return r;
}

TEST(EvalExperiment, RunsSummarisedPerViewCount) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The third run stops a step early; the second's first step failed (NaN accuracy, nothing complete).
  const std::vector<LoopResult> runs = {run_of({0.2, 0.4, 0.6}, {1, 0.5, 0.25}),
                                        run_of({0.0, 0.6, 0.8}, {nan, 0.7, 0.35}),
                                        run_of({0.1, 0.5}, {2, 0.6})};
  const auto rows = summarize_runs(runs);
  auto find = [&](std::size_t views, const std::string& metric) {
    for (const auto& r : rows)
      if (r.num_views == views && r.metric == metric) return r.value;
    ADD_FAILURE() << "no row " << views << " " << metric;
    return MeanInterval{};
  };
  EXPECT_EQ(rows.size(), 3u * 4u);  // 3 view counts x {accuracy_90, completeness_0.01, mean_accuracy, faces}
  EXPECT_EQ(find(3, "completeness_0.01").n, 3u);
  EXPECT_NEAR(find(3, "completeness_0.01").mean, 0.1, 1e-12);
  EXPECT_EQ(find(3, "accuracy_90").n, 2u);  // the failed step has no accuracy
  EXPECT_NEAR(find(3, "accuracy_90").mean, 1.5, 1e-12);
  EXPECT_EQ(find(5, "completeness_0.01").n, 2u);
  EXPECT_NEAR(find(5, "completeness_0.01").mean, 0.7, 1e-12);
  EXPECT_NEAR(find(4, "faces").mean, 200, 1e-12);
  EXPECT_NEAR(find(4, "mean_accuracy").mean, 0.3, 1e-12);
  // Two runs at 5 views: mean 0.7, s = 0.1414, t(1) = 12.706.
  const MeanInterval five = find(5, "completeness_0.01");
  EXPECT_NEAR(five.high - five.mean, student_t_critical(1) * std::sqrt(0.02) / std::sqrt(2.0), 1e-12);

  const std::string csv = runs_csv(rows);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "num_views,metric,runs,mean,ci_low,ci_high,min,max");
  EXPECT_NE(csv.find("\n5,completeness_0.01,2,0.7,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n3,accuracy_90,2,1.5,"), std::string::npos) << csv;

  // Areas: the mean of each run's curve (0.4, 0.4667, 0.3).
  const auto areas = summarize_curve_areas(runs);
  ASSERT_EQ(areas.size(), 1u);
  EXPECT_EQ(areas[0].first, "completeness_0.01");
  EXPECT_EQ(areas[0].second.n, 3u);
  EXPECT_NEAR(areas[0].second.mean, (0.4 + 1.4 / 3 + 0.3) / 3, 1e-12);
}

TEST(EvalExperiment, BootstrapSeeds) {
  EXPECT_EQ(bootstrap_seed(42, 1), 42u);
  std::set<std::uint64_t> seen;
  for (int b = 1; b <= 100; ++b) {
    seen.insert(bootstrap_seed(42, b));
    EXPECT_LT(bootstrap_seed(42, b), 2147483648u);
  }
  EXPECT_EQ(seen.size(), 100u);
  EXPECT_NE(bootstrap_seed(42, 2), bootstrap_seed(43, 2));
}

}  // namespace
}  // namespace meshnbv::eval
