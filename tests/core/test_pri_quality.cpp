// PRI against ground truth on rendered synthetic scenes: the truth is
// photo-consistent, and PRI finds the degraded faces.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "meshnbv/pri.h"
#include "meshnbv/synth/project.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

// Average ranks (1-based), ties sharing their mean rank.
std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < idx.size();) {
    std::size_t j = i;
    while (j + 1 < idx.size() && v[idx[j + 1]] == v[idx[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[idx[k]] = 0.5 * double(i + j) + 1.0;
    i = j + 1;
  }
  return r;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const auto ra = ranks(a), rb = ranks(b);
  const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / ra.size();
  const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / rb.size();
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - ma) * (rb[i] - mb);
    saa += (ra[i] - ma) * (ra[i] - ma);
    sbb += (rb[i] - mb) * (rb[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// ROC AUC of `score` for the positives, by the Mann-Whitney statistic.
double roc_auc(const std::vector<double>& score, const std::vector<bool>& positive) {
  const auto r = ranks(score);
  double sum_pos = 0, n_pos = 0, n_neg = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (positive[i]) sum_pos += r[i], ++n_pos;
    else ++n_neg;
  }
  return (sum_pos - n_pos * (n_pos + 1) / 2) / (n_pos * n_neg);
}

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

// A synthetic project for the quality tests: 16 orbit views at 1280x960
// (one sample per pixel: the textures are band-limited), faces of about
// 12 px, and one degradation centred on a facade every camera ring sees.
synth::SynthProject project(const std::string& scene, const std::string& degradation) {
  synth::SynthOptions o;
  o.scene = scene;
  o.generator.edge_length = scene == "building" ? 0.5 : 1.2;
  o.cameras.count = 16;
  o.cameras.layout = synth::CameraLayout::Orbit;
  o.cameras.width = 1280;
  o.cameras.height = 960;
  o.render.samples_per_pixel = 1;
  synth::Degradation d = synth::parse_degradation(degradation);
  // The south facade of the building; the east curtain wall of the fortress.
  d.center = scene == "building" ? Vec3(0, -3.45, 5) : Vec3(16, 0, 4);
  o.degradations = {d};
  o.overwrite = true;
  return synth::write_synthetic_project(o, test::temp_dir("pri_" + scene + "_" + degradation.substr(0, 4) + std::to_string(degradation.size())));
}

}  // namespace

// What each case must reach, for SSD and NCC. The targets are
// AUC >= 0.85 and Spearman >= 0.5. Spearman is asserted over the faces of
// the degraded region (ground-truth error > 0): over all faces the
// undegraded majority ties at zero error and caps it (docs/pri.md). The
// all-faces Spearman floors, and the floors of the whole-mesh noise cases
// (no undegraded face; errors of 0-4 px), are what this implementation
// reaches with a margin (docs/pri.md has the measured table), so that a
// regression fails the test.
struct Floors {
  double auc_ssd, auc_ncc;
  double rho_region_ssd, rho_region_ncc;
  double rho_ssd, rho_ncc;
};
class PriFindsDegradation
    : public ::testing::TestWithParam<std::tuple<std::string, std::string, Floors>> {};

TEST_P(PriFindsDegradation, AucAndSpearman) {
  const auto& [scene, degradation, floors] = GetParam();
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
    EXPECT_GE(q.auc, ssd ? floors.auc_ssd : floors.auc_ncc) << measure_name(m);
    EXPECT_GE(q.rho_region, ssd ? floors.rho_region_ssd : floors.rho_region_ncc) << measure_name(m);
    EXPECT_GE(q.rho, ssd ? floors.rho_ssd : floors.rho_ncc) << measure_name(m);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Synthetic, PriFindsDegradation,
    ::testing::Values(
        // Local degradations centred on a facade: the targets.
        std::make_tuple("building", "noise:0.01:0.3", Floors{0.85, 0.85, 0.5, 0.5, 0.4, 0.48}),
        std::make_tuple("building", "dent:0.03:0.2", Floors{0.85, 0.85, 0.5, 0.5, 0.35, 0.37}),
        std::make_tuple("fortress", "noise:0.01:0.3", Floors{0.85, 0.85, 0.5, 0.5, 0.42, 0.45}),
        std::make_tuple("fortress", "bump:0.02:0.2", Floors{0.85, 0.85, 0.5, 0.5, 0.13, 0.22}),
        // Noise over the whole mesh (radius 3 diagonals): measured floors.
        std::make_tuple("building", "noise:0.005:3", Floors{0.6, 0.65, 0.24, 0.38, 0.24, 0.38}),
        std::make_tuple("fortress", "noise:0.005:3", Floors{0.6, 0.65, 0.25, 0.34, 0.25, 0.34})),
    [](const auto& info) {
      const std::string& d = std::get<1>(info.param);
      const bool whole = d.size() >= 2 && d.compare(d.size() - 2, 2, ":3") == 0;
      return std::get<0>(info.param) + "_" + d.substr(0, d.find(':')) + (whole ? "_whole" : "");
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
            << st.percentiles[5].second << "; median over the dented faces " << wrong_median << "\n";
  EXPECT_LT(st.percentiles[3].second, 1e-4);  // mean squared luminance difference
  EXPECT_LT(st.percentiles[5].second, 5e-3);
  EXPECT_GT(wrong_median, 10 * st.percentiles[3].second);
  EXPECT_GT(on_truth.observed, p.truth.num_faces() / 2);
}
