// PRI against ground truth on rendered synthetic scenes: the truth is
// photo-consistent, and PRI finds the degraded faces.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "meshnbv/eval/ranking.h"
#include "meshnbv/pri.h"
#include "meshnbv/synth/project.h"
#include "pri_quality_scene.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

using eval::roc_auc;
using eval::spearman;

struct Quality {
  double auc = 0, rho = 0, rho_region = 0;
  std::size_t observed = 0, positives = 0, region = 0;
};

Quality evaluate(const PriResult& r, const std::vector<float>& gt_error, double threshold) {
  Quality q;
  std::vector<double> score, error, rscore, rerror;
  std::vector<bool> positive;
  for (std::size_t f = 0; f < r.pri.size(); ++f)
    if (r.status[f] == FaceStatus::Observed) {
      score.push_back(r.pri[f]);
      error.push_back(gt_error[f]);
      positive.push_back(gt_error[f] > threshold);
      if (gt_error[f] > 1e-3 * threshold) {
        rscore.push_back(r.pri[f]);
        rerror.push_back(gt_error[f]);
      }
    }
  q.region = rscore.size();
  q.rho_region = spearman(rscore, rerror);
  q.observed = score.size();
  q.positives = std::size_t(std::count(positive.begin(), positive.end(), true));
  q.auc = roc_auc(score, positive);
  q.rho = spearman(score, error);
  return q;
}

// A synthetic project for the quality tests (pri_quality_scene.h), on disk.
synth::SynthProject project(const std::string& scene, const std::string& degradation) {
  synth::SynthOptions o = test::pri_quality_options(scene, degradation);
  o.overwrite = true;
  return synth::write_synthetic_project(o, test::temp_dir("pri_" + scene + "_" + degradation.substr(0, 4) + std::to_string(degradation.size())));
}

}  // namespace

// What each case must reach, for SSD and NCC. Every floor is the value
// measured on 2026-12-01 (Release build, default options; the same to all
// printed digits in two runs and in docs/pri.md's run of 2026-11-22: the
// renders and PRI are deterministic) minus a stated margin:
//   floor = measured - 0.02 for AUC, measured - 0.03 for Spearman.
// The margin leaves room for changes that merely reorder near-equal PRI
// values (e.g. a different summation order), not for noise; a larger loss
// is a regression. Do not lower a floor to make the test pass: re-measure,
// and say in the commit why the quality changed.
// The issue's targets, AUC >= 0.85 and Spearman >= 0.5 over the degraded
// region (faces with ground-truth error > 0: over all faces the undegraded
// majority ties at zero error and caps it, docs/pri.md), are asserted as
// well on the four local degradations, where docs/pri.md says they are met.
struct Measured {  // measured on 2026-12-01, truncated to 3 decimals
  double auc_ssd, auc_ncc;
  double rho_region_ssd, rho_region_ncc;
  double rho_ssd, rho_ncc;
  bool issue_targets;  // the case is one of those the issue's targets are for
};
// Readable test names in ctest (instead of a byte dump of the struct).
void PrintTo(const Measured& m, std::ostream* os) {
  *os << "measured AUC " << m.auc_ssd << "/" << m.auc_ncc << ", Spearman region "
      << m.rho_region_ssd << "/" << m.rho_region_ncc << ", all " << m.rho_ssd << "/" << m.rho_ncc;
}
constexpr double kAucMargin = 0.02, kRhoMargin = 0.03;
constexpr double kTargetAuc = 0.85, kTargetRho = 0.5;

class PriFindsDegradation
    : public ::testing::TestWithParam<std::tuple<std::string, std::string, Measured>> {};

TEST_P(PriFindsDegradation, AucAndSpearman) {
  const auto& [scene, degradation, measured] = GetParam();
  synth::SynthProject p = project(scene, degradation);
  // Positives: faces whose ground-truth error exceeds 0.3% of the scene
  // diagonal (about 1.3 px at the cameras' distance).
  const double threshold = 0.003 * p.truth.bounding_box().diagonal();
  for (Measure m : {Measure::SSD, Measure::NCC}) {
    PriOptions o;
    o.measure = m;
    const PriResult r = compute_pri(p.scene, o);
    const Quality q = evaluate(r, p.gt_error, threshold);
    std::cout << scene << " " << degradation << " " << measure_name(m) << ": AUC " << q.auc
              << ", Spearman over the degraded region " << q.rho_region << " (" << q.region
              << " faces), over all faces " << q.rho << " (" << q.observed << " observed faces, "
              << q.positives << " with error > " << threshold << " m)\n";
    const bool ssd = m == Measure::SSD;
    ASSERT_GT(q.positives, 100u);
    EXPECT_GE(q.auc, (ssd ? measured.auc_ssd : measured.auc_ncc) - kAucMargin) << measure_name(m);
    EXPECT_GE(q.rho_region, (ssd ? measured.rho_region_ssd : measured.rho_region_ncc) - kRhoMargin)
        << measure_name(m);
    EXPECT_GE(q.rho, (ssd ? measured.rho_ssd : measured.rho_ncc) - kRhoMargin) << measure_name(m);
    if (measured.issue_targets) {
      EXPECT_GE(q.auc, kTargetAuc) << measure_name(m) << ": the issue's target";
      EXPECT_GE(q.rho_region, kTargetRho) << measure_name(m) << ": the issue's target";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Synthetic, PriFindsDegradation,
    ::testing::Values(
        // Measured{AUC SSD, AUC NCC, Spearman region SSD, NCC, Spearman all SSD, NCC}.
        // Local degradations centred on a facade: the issue's targets.
        std::make_tuple("building", "noise:0.01:0.3",
                        Measured{0.900, 0.973, 0.639, 0.817, 0.455, 0.537, true}),
        std::make_tuple("building", "dent:0.03:0.2",
                        Measured{0.994, 0.998, 0.775, 0.860, 0.404, 0.423, true}),
        // NCC's AUC here (0.860) is within the margin of the issue's 0.85:
        // the target, asserted separately, is the binding floor.
        std::make_tuple("fortress", "noise:0.01:0.3",
                        Measured{0.875, 0.860, 0.589, 0.541, 0.471, 0.497, true}),
        std::make_tuple("fortress", "bump:0.02:0.2",
                        Measured{0.974, 0.981, 0.747, 0.830, 0.175, 0.271, true}),
        // Noise over the whole mesh (radius 3 diagonals; every face degraded,
        // so region = all faces).
        std::make_tuple("building", "noise:0.005:3",
                        Measured{0.628, 0.702, 0.288, 0.430, 0.288, 0.430, false}),
        std::make_tuple("fortress", "noise:0.005:3",
                        Measured{0.645, 0.690, 0.295, 0.391, 0.295, 0.391, false})),
    [](const auto& param_info) {
      const std::string& d = std::get<1>(param_info.param);
      const bool whole = d.size() >= 2 && d.compare(d.size() - 2, 2, ":3") == 0;
      return std::get<0>(param_info.param) + "_" + d.substr(0, d.find(':')) + (whole ? "_whole" : "");
    });

TEST(PriQuality, TruthIsNearZero) {
  synth::SynthProject p = project("building", "dent:0.03:0.2");
  Scene truth = p.scene;
  truth.mesh = p.truth;
  const PriResult on_truth = compute_pri(truth, {});
  const PriResult on_degraded = compute_pri(p.scene, {});
  const PriSummary st = summarize_pri(on_truth);
  // percentiles: 0, 5, 25, 50, 75, 95, 99, 100
  const double threshold = 0.003 * p.truth.bounding_box().diagonal();
  std::vector<float> wrong;
  for (std::size_t f = 0; f < p.gt_error.size(); ++f)
    if (p.gt_error[f] > threshold && on_degraded.status[f] == FaceStatus::Observed)
      wrong.push_back(on_degraded.pri[f]);
  ASSERT_GT(wrong.size(), 100u);
  std::nth_element(wrong.begin(), wrong.begin() + wrong.size() / 2, wrong.end());
  const double wrong_median = wrong[wrong.size() / 2];
  std::cout << "SSD on truth: median " << st.percentiles[3].second << ", 95% "
            << st.percentiles[5].second << "; median over the dented faces " << wrong_median
            << " (" << wrong.size() << " faces); " << on_truth.observed << " of "
            << p.truth.num_faces() << " faces observed on the truth\n";
  // Bounds from the values measured on 2026-12-01 (deterministic, as
  // above). SSD levels span orders of magnitude, so their margin is a
  // factor of 2; the observed share has a margin of 0.02.
  // Median SSD on the truth: measured 2.45e-6, ceiling = 2 x measured.
  EXPECT_LT(st.percentiles[3].second, 4.9e-6);  // mean squared luminance difference
  // 95th percentile on the truth: measured 1.91e-4, ceiling = 2 x measured.
  EXPECT_LT(st.percentiles[5].second, 3.8e-4);
  // Median over the dented faces: measured 3.77e-3, floor = measured / 2
  // (together with the ceiling above: over 380 times the truth's median).
  EXPECT_GT(wrong_median, 1.88e-3);
  // Faces observed on the truth: measured 4068 of 5284 = 0.770, floor =
  // measured share - 0.02.
  EXPECT_GE(double(on_truth.observed), 0.75 * double(p.truth.num_faces()));
}
