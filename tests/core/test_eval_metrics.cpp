// Middlebury-style metrics against meshes with known distances.
// Geometry: a unit square in the plane z = 0 (grid of triangles) and copies
// of it shifted along z; distances between parallel, equally large planes
// are exactly the shift for every sample.
#include <gtest/gtest.h>

#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/eval/metrics.h"
#include "meshnbv/synth/generators.h"
#include "test_util.h"

namespace meshnbv::eval {
namespace {

// Square [x0, x1] x [0, 1] at height z, split into n x n cells.
TriangleMesh square(double x0, double x1, double z, int n = 4) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.vertices.emplace_back(x0 + (x1 - x0) * i / n, double(j) / n, z);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  return m;
}

TEST(EvalMetrics, PercentileInterpolatesLikeNumpy) {
  std::vector<double> v{5, 1, 4, 2, 3};
  EXPECT_DOUBLE_EQ(percentile(v, 50), 3.0);
  EXPECT_DOUBLE_EQ(percentile(v, 80), 4.2);  // position 3.2 between 4 and 5
  EXPECT_DOUBLE_EQ(percentile(v, 100), 5.0);
  EXPECT_DOUBLE_EQ(percentile(v, 0), 1.0);
  std::vector<double> empty;
  EXPECT_TRUE(std::isnan(percentile(empty, 50)));
}

TEST(EvalMetrics, SamplingIsAreaUniformAndDeterministic) {
  const TriangleMesh m = square(0, 1, 0);
  const auto a = sample_surface(m, 0.01, 7);
  const auto b = sample_surface(m, 0.01, 7);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(double(a.size()), 10000.0, 100.0);  // area / spacing^2, one rounding per face
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
  std::size_t left = 0;
  for (const Vec3& p : a) {
    EXPECT_GE(p.x(), 0.0);
    EXPECT_LE(p.x(), 1.0);
    EXPECT_DOUBLE_EQ(p.z(), 0.0);
    if (p.x() < 0.25) ++left;
  }
  EXPECT_NEAR(double(left) / double(a.size()), 0.25, 0.02);
}

TEST(EvalMetrics, OffsetPlaneHasAccuracyEqualToTheOffset) {
  const TriangleMesh reference = square(0, 1, 0);
  const TriangleMesh recon = square(0, 1, 0.002);
  EvaluationOptions o;
  o.thresholds = {0.001, 0.0025, 0.005};
  o.sample_spacing = 0.01;
  const EvaluationResult r = evaluate_reconstruction(recon, reference, o);
  ASSERT_EQ(r.accuracy.size(), 3u);
  for (const auto& [p, d] : r.accuracy) EXPECT_NEAR(d, 0.002, 1e-9) << "percentile " << p;
  EXPECT_NEAR(r.mean_accuracy, 0.002, 1e-9);
  ASSERT_EQ(r.completeness.size(), 3u);
  EXPECT_DOUBLE_EQ(r.completeness[0].second, 0.0);  // 1 mm < 2 mm offset
  EXPECT_DOUBLE_EQ(r.completeness[1].second, 1.0);
  EXPECT_DOUBLE_EQ(r.completeness[2].second, 1.0);
  EXPECT_NEAR(r.reference_area, 1.0, 1e-12);
  EXPECT_GT(r.reference_samples, 9000u);
}

TEST(EvalMetrics, HalfReconstructionIsHalfComplete) {
  const TriangleMesh reference = square(0, 1, 0);
  const TriangleMesh recon = square(0, 0.5, 0);
  EvaluationOptions o;
  o.thresholds = {1e-6, 0.1, 0.6};
  o.sample_spacing = 0.005;
  const EvaluationResult r = evaluate_reconstruction(recon, reference, o);
  for (const auto& [p, d] : r.accuracy) EXPECT_NEAR(d, 0.0, 1e-9);  // on the reference
  EXPECT_NEAR(r.completeness[0].second, 0.5, 0.01);
  // Samples at x in (0.5, 0.6] are within 0.1 of the half square.
  EXPECT_NEAR(r.completeness[1].second, 0.6, 0.01);
  EXPECT_DOUBLE_EQ(r.completeness[2].second, 1.0);
}

TEST(EvalMetrics, AccuracyPercentilesOfATiltedReconstruction) {
  // Reconstruction: the square tilted about the x axis, z = 0.01 y: the
  // distance of a sample at y to the reference plane is 0.01 y / sqrt(1 +
  // 1e-4) ~ 0.01 y, uniform in y, so its p-th percentile is ~0.01 p/100.
  const TriangleMesh reference = square(-1, 2, 0, 6);
  TriangleMesh recon = square(0, 1, 0);
  for (Vec3& v : recon.vertices) v.z() = 0.01 * v.y();
  EvaluationOptions o;
  o.sample_spacing = 0.004;
  const EvaluationResult r = evaluate_reconstruction(recon, reference, o);
  EXPECT_NEAR(r.accuracy[0].second, 0.008, 2e-4);
  EXPECT_NEAR(r.accuracy[1].second, 0.009, 2e-4);
  EXPECT_NEAR(r.accuracy[2].second, 0.0099, 2e-4);
}

TEST(EvalMetrics, EmptyReconstructionIsNotAnError) {
  const TriangleMesh reference = square(0, 1, 0);
  const EvaluationResult r = evaluate_reconstruction(TriangleMesh{}, reference);
  for (const auto& [p, d] : r.accuracy) EXPECT_TRUE(std::isnan(d));
  for (const auto& [t, c] : r.completeness) EXPECT_EQ(c, 0.0);
  EXPECT_EQ(r.reconstruction_samples, 0u);
}

TEST(EvalMetrics, OptionsAreChecked) {
  const TriangleMesh m = square(0, 1, 0);
  EvaluationOptions o;
  o.thresholds = {0.001, -1};
  MESHNBV_EXPECT_ERROR_CONTAINS(evaluate_reconstruction(m, m, o), "thresholds must be positive");
  o = {};
  o.percentiles = {0};
  MESHNBV_EXPECT_ERROR_CONTAINS(evaluate_reconstruction(m, m, o), "percentiles must be in (0, 100]");
  MESHNBV_EXPECT_ERROR_CONTAINS(evaluate_reconstruction(m, TriangleMesh{}, {}), "no area");
}

TEST(EvalMetrics, ObservablePartDropsWhatNoCameraSees) {
  // A closed box on the ground seen from a ring of cameras above the
  // horizon: its bottom is never seen.
  const TriangleMesh box = synth::make_box(Vec3(-1, -1, 0), Vec3(1, 1, 2), 0.5, 0);
  std::vector<PinholeCamera> cams;
  for (int k = 0; k < 8; ++k) {
    const double a = 2 * M_PI * k / 8;
    cams.push_back(PinholeCamera::look_at(Vec3(8 * std::cos(a), 8 * std::sin(a), 5), Vec3(0, 0, 1),
                                          Vec3(0, 0, 1), 500, 500, 319.5, 239.5, 640, 480));
  }
  const TriangleMesh seen = observable_part(box, cams, 1);
  std::size_t bottom = 0;
  for (std::size_t f = 0; f < box.num_faces(); ++f)
    if (box.face_normal(f).z() < -0.9) ++bottom;
  EXPECT_EQ(seen.num_faces(), box.num_faces() - bottom);
  for (std::size_t f = 0; f < seen.num_faces(); ++f) EXPECT_GT(seen.face_normal(f).z(), -0.9);
}

}  // namespace
}  // namespace meshnbv::eval
