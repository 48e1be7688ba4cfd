// PRI against ground truth, written to a result file (issue #20): the
// figures of docs/pri.md's "How well it works", of the `max_incidence_angle`
// and `edge_margin` rows of docs/deviations.md and of the band limit in
// docs/synthetic.md.
//
//   pri_quality [OUT.json]        (default bench/results/pri_quality.json)
//
// The scenes and cases are those of tests/core/test_pri_quality.cpp (16
// orbit views at 1280x960, one sample per pixel, faces of about 12 px, one
// degradation centred on a facade; positives: ground-truth error > 0.3% of
// the diagonal; Spearman over the degraded region and over all observed
// faces). The images are rendered in memory exactly as `meshnbv synth`
// renders them (same texture and band limit), so the figures equal the
// test's. In the same run:
//  - every case with SSD and NCC at the default options, and the four local
//    cases again with edge_margin 0 (the SPEC's lattice);
//  - PRI on the ground-truth building (the test's TruthIsNearZero project):
//    percentiles at the defaults, with edge_margin 0, with
//    max_incidence_angle 90, and on images rendered without the texture's
//    band limit; the median over the dented faces of the degraded mesh.
// About 30 s on 2 cores (Release; `seconds` in the result file).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshnbv/eval/ranking.h"
#include "meshnbv/pri.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/synth/generators.h"
#include "meshnbv/synth/project.h"
#include "meshnbv/texture.h"
#include "pri_quality_scene.h"

using namespace meshnbv;
using json = nlohmann::ordered_json;

namespace {

// As libs/synth/src/project.cpp: the finest texture period, in pixels at the
// median camera distance.
constexpr double kBandLimitPixels = 8.0;

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

using eval::roc_auc;
using eval::spearman;

// Linear-interpolation percentile (numpy's default) of unsorted values.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double x = p / 100.0 * double(v.size() - 1);
  const std::size_t i = std::size_t(std::floor(x));
  const double f = x - double(i);
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

struct Project {
  synth::SynthProject p;
  double footprint = 0;  // metres per pixel at the median camera distance
  double threshold = 0;  // positives: ground-truth error above this (m)
  double edge_length = 0;  // the generator's edge_length option (m)
  double median_edge = 0;  // median edge of the truth's faces (m)
  synth::SynthOptions options;
};

// The test's project (tests/core/test_pri_quality.cpp, project()), without
// files: meshes, cameras and ground truth from make_synthetic_project.
Project make_project(const std::string& scene, const std::string& degradation) {
  Project r;
  r.options = test::pri_quality_options(scene, degradation);
  const synth::SynthOptions& o = r.options;
  r.p = synth::make_synthetic_project(o);
  r.edge_length = o.generator.edge_length;
  std::vector<double> footprint;
  const Vec3 centre = r.p.truth.bounding_box().center();
  for (const auto& v : r.p.scene.views)
    footprint.push_back((v.camera.center() - centre).norm() / v.camera.fx);
  std::nth_element(footprint.begin(), footprint.begin() + footprint.size() / 2, footprint.end());
  r.footprint = footprint[footprint.size() / 2];
  r.threshold = 0.003 * r.p.truth.bounding_box().diagonal();
  std::vector<double> edges;
  const auto& V = r.p.truth.vertices;
  for (const auto& f : r.p.truth.faces)
    for (int k = 0; k < 3; ++k) edges.push_back((V[f[k]] - V[f[(k + 1) % 3]]).norm());
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  r.median_edge = edges[edges.size() / 2];
  return r;
}

// Renders every view of the project into memory (View::pixels), as
// write_synthetic_project renders its PNGs; band_limited = false drops the
// texture's band limit (min_period 0).
void render_views(Project& pr, bool band_limited) {
  const RayCaster caster(pr.p.truth);
  const SolidTexture texture(pr.options.seed, default_materials(),
                             band_limited ? kBandLimitPixels * pr.footprint : 0.0);
  RenderInputs in{&pr.p.truth, &caster, &texture, pr.p.truth.face_attribute(synth::kMaterialAttribute)};
  for (auto& v : pr.p.scene.views) {
    v.image_path.clear();
    v.pixels = std::make_shared<const Image>(render(in, v.camera, pr.options.render));
  }
}

json quality(const Project& pr, const PriResult& r) {
  const auto& gt = pr.p.gt_error;
  std::vector<double> score, error, rscore, rerror;
  std::vector<bool> positive;
  for (std::size_t f = 0; f < r.pri.size(); ++f)
    if (r.status[f] == FaceStatus::Observed) {
      score.push_back(r.pri[f]);
      error.push_back(gt[f]);
      positive.push_back(gt[f] > pr.threshold);
      if (gt[f] > 1e-3 * pr.threshold) {
        rscore.push_back(r.pri[f]);
        rerror.push_back(gt[f]);
      }
    }
  const std::size_t positives = std::size_t(std::count(positive.begin(), positive.end(), true));
  json q;
  q["auc"] = roc_auc(score, positive);
  q["spearman_region"] = spearman(rscore, rerror);
  q["spearman_all"] = spearman(score, error);
  q["observed_faces"] = score.size();
  q["region_faces"] = rscore.size();
  q["positives"] = positives;
  // Observed faces outside the degraded region (error <= 1e-3 x threshold):
  // they tie at (nearly) zero error.
  q["zero_error_share"] = 1.0 - double(rscore.size()) / double(score.size());
  q["pri_seconds"] = r.seconds;
  return q;
}

json summary(const PriResult& r) {
  std::vector<double> v;
  for (std::size_t f = 0; f < r.pri.size(); ++f)
    if (r.status[f] == FaceStatus::Observed) v.push_back(r.pri[f]);
  json s;
  s["observed_faces"] = v.size();
  s["faces"] = r.pri.size();
  for (double p : {50.0, 95.0, 99.0, 100.0}) s["p" + std::to_string(int(p))] = percentile(v, p);
  return s;
}

std::string fmt(double x, int digits = 3) {
  char b[32];
  std::snprintf(b, sizeof(b), "%.*f", digits, x);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "bench/results/pri_quality.json";
  const double t0 = now_s();
  json result;
  char host[256] = {};
  gethostname(host, sizeof(host) - 1);
  char date[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%S+00:00", std::gmtime(&t));
  result["date"] = date;
  result["host"] = host;
  result["threads"] = std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
  result["program"] = "bench/pri_quality.cpp";
  result["setup"] = {
      {"views", 16}, {"layout", "orbit"}, {"size", "1280x960"}, {"samples_per_pixel", 1},
      {"edge_length_m", {{"building", 0.5}, {"fortress", 1.2}}},
      {"positives", "ground-truth error > 0.3% of the bounding-box diagonal"},
      {"region", "faces with ground-truth error > 1e-3 x the positive threshold"},
      {"options", "PriOptions defaults unless a case says otherwise"},
      {"pixels", "*_px: metres over the footprint, the metres per pixel at the median distance from "
                 "the cameras to the bounding-box centre (the texture's band limit is 8 of them)"}};

  struct Case {
    const char* scene;
    const char* degradation;
    bool local;
  };
  const Case cases[] = {{"building", "noise:0.01:0.3", true}, {"building", "dent:0.03:0.2", true},
                        {"fortress", "noise:0.01:0.3", true}, {"fortress", "bump:0.02:0.2", true},
                        {"building", "noise:0.005:3", false}, {"fortress", "noise:0.005:3", false}};
  json rows = json::array();
  std::cout << "| scene | degradation | edge_margin | AUC SSD | AUC NCC | Spearman SSD region / all | "
               "Spearman NCC region / all |\n|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases) {
    Project pr = make_project(c.scene, c.degradation);
    render_views(pr, true);
    std::vector<double> err_px;
    for (float e : pr.p.gt_error) err_px.push_back(e / pr.footprint);
    json row;
    row["scene"] = c.scene;
    row["degradation"] = c.degradation;
    row["local"] = c.local;
    row["faces"] = pr.p.scene.mesh.num_faces();
    row["diagonal_m"] = pr.p.truth.bounding_box().diagonal();
    row["threshold_m"] = pr.threshold;
    row["footprint_m_per_px"] = pr.footprint;
    row["threshold_px"] = pr.threshold / pr.footprint;
    row["edge_length_option_m"] = pr.edge_length;
    row["median_edge_m"] = pr.median_edge;
    row["median_edge_px"] = pr.median_edge / pr.footprint;
    row["error_px"] = {{"p50", percentile(err_px, 50)}, {"p99", percentile(err_px, 99)},
                       {"max", percentile(err_px, 100)}};
    for (double margin : c.local ? std::vector<double>{0.5, 0.0} : std::vector<double>{0.5}) {
      json by_measure;
      for (Measure m : {Measure::SSD, Measure::NCC}) {
        PriOptions o;
        o.measure = m;
        o.edge_margin = margin;
        by_measure[measure_name(m)] = quality(pr, compute_pri(pr.p.scene, o));
      }
      row[margin > 0 ? "edge_margin_0.5" : "edge_margin_0"] = by_measure;
      const json& s = by_measure["ssd"];
      const json& n = by_measure["ncc"];
      std::cout << "| " << c.scene << " | " << c.degradation << " | " << margin << " | "
                << fmt(s["auc"]) << " | " << fmt(n["auc"]) << " | " << fmt(s["spearman_region"]) << " / "
                << fmt(s["spearman_all"]) << " | " << fmt(n["spearman_region"]) << " / "
                << fmt(n["spearman_all"]) << " |" << std::endl;
    }
    rows.push_back(row);
  }
  result["cases"] = rows;

  // The ground-truth building of the test's TruthIsNearZero (dent project).
  {
    Project pr = make_project("building", "dent:0.03:0.2");
    render_views(pr, true);
    Scene truth = pr.p.scene;
    truth.mesh = pr.p.truth;
    json tr;
    tr["project"] = "building, dent:0.03:0.2 (the truth replaces the degraded mesh)";
    tr["defaults"] = summary(compute_pri(truth, {}));
    PriOptions no_margin;
    no_margin.edge_margin = 0;
    tr["edge_margin_0"] = summary(compute_pri(truth, no_margin));
    PriOptions grazing;
    grazing.max_incidence_angle = 90;
    tr["max_incidence_angle_90"] = summary(compute_pri(truth, grazing));
    PriOptions grazing_no_margin = grazing;
    grazing_no_margin.edge_margin = 0;
    tr["max_incidence_angle_90_edge_margin_0"] = summary(compute_pri(truth, grazing_no_margin));
    // The median PRI over the dented faces (error > threshold) of the degraded mesh.
    const PriResult degraded = compute_pri(pr.p.scene, {});
    std::vector<double> wrong;
    for (std::size_t f = 0; f < pr.p.gt_error.size(); ++f)
      if (pr.p.gt_error[f] > pr.threshold && degraded.status[f] == FaceStatus::Observed)
        wrong.push_back(degraded.pri[f]);
    tr["dented_faces"] = {{"faces", wrong.size()}, {"p50", percentile(wrong, 50)}};
    // The same truth on images rendered without the texture's band limit.
    render_views(pr, false);
    truth = pr.p.scene;
    truth.mesh = pr.p.truth;
    tr["no_band_limit"] = summary(compute_pri(truth, {}));
    result["truth_ssd"] = tr;
    std::cout << "\nSSD PRI on the ground-truth building:\n" << tr.dump(1) << "\n";
  }
  result["seconds"] = now_s() - t0;
  std::ofstream f(out);
  f << result.dump(1) << "\n";
  if (!f) {
    std::cerr << "cannot write " << out << "\n";
    return 1;
  }
  std::cout << "wrote " << out << " (" << fmt(now_s() - t0, 0) << " s)\n";
  return 0;
}
