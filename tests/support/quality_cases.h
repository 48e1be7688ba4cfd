// The cases of the quality-index bench (bench/quality/, issue #14), shared
// with the test that asserts its figures (tests/core/test_quality_index.cpp):
// 16 orbit views at 1280x960, one sample per pixel.
//  - field: a smooth displacement over the whole mesh (sum of Gaussian
//    bumps of random sign and size) plus noise, of a peak given in pixels
//    at the cameras' median distance;
//  - local: one dent or bump centred on a facade (the cases of docs/pri.md);
//  - recon: the scene reconstructed from its own rendered views by the
//    evaluation loop's backend (COLMAP points, Delaunay visibility mesher).
#pragma once

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/eval/quality.h"
#include "meshnbv/pri.h"

#include "meshnbv/synth/project.h"

namespace meshnbv::test {

struct QualityCase {
  std::string name;   // e.g. "field_building_1px"
  std::string kind;   // field | local | recon
  std::string scene;  // building | fortress | city
  double edge_length = 0;  // generator's edge length (m)
  std::string degradation;  // local: kind:strength:radius
  double peak_px = 0;       // field: peak displacement in pixels
};

// gtest prints a case by its name.
inline void PrintTo(const QualityCase& c, std::ostream* os) { *os << c.name; }

inline std::vector<QualityCase> quality_cases() {
  std::vector<QualityCase> out;
  for (double px : {0.5, 1.0, 2.0}) {
    const std::string tag = px == 0.5 ? "0.5px" : std::to_string(int(px)) + "px";
    out.push_back({"field_building_" + tag, "field", "building", 0.25, "", px});
    out.push_back({"field_fortress_" + tag, "field", "fortress", 0.6, "", px});
  }
  out.push_back({"local_building_dent", "local", "building", 0.5, "dent:0.03:0.2", 0});
  out.push_back({"local_fortress_bump", "local", "fortress", 1.2, "bump:0.02:0.2", 0});
  for (const char* scene : {"building", "fortress", "city"})
    out.push_back({std::string("recon_") + scene, "recon", scene, 0, "", 0});
  return out;
}

// Synthesis options of a case (without its degradation for field cases:
// its strength depends on the cameras' footprint, see the bench).
inline synth::SynthOptions quality_case_options(const QualityCase& c) {
  synth::SynthOptions o;
  o.scene = c.scene;
  o.generator.edge_length = c.edge_length;
  o.cameras.count = 16;
  o.cameras.layout = synth::CameraLayout::Orbit;
  o.cameras.width = 1280;
  o.cameras.height = 960;
  o.render.samples_per_pixel = 1;
  if (c.kind == "local") {
    synth::Degradation d = synth::parse_degradation(c.degradation);
    d.center = c.scene == "building" ? Vec3(0, -3.45, 5) : Vec3(16, 0, 4);
    o.degradations = {d};
  }
  return o;
}

// Scene units per pixel at the median distance from the cameras to the
// truth's bounding-box centre.
inline double footprint_of(const Scene& scene, const TriangleMesh& truth) {
  std::vector<double> fp;
  const Vec3 centre = truth.bounding_box().center();
  for (const auto& v : scene.views) fp.push_back((v.camera.center() - centre).norm() / v.camera.fx);
  std::nth_element(fp.begin(), fp.begin() + std::ptrdiff_t(fp.size() / 2), fp.end());
  return fp[fp.size() / 2];
}

// A prepared case: the scene to compute an index on (its mesh, the views
// with their images in memory), the truth and each face's true error.
struct PreparedCase {
  Scene scene;
  TriangleMesh truth;
  std::vector<float> error;
  double footprint = 0;
};

// A field or local case, generated and rendered (no files).
inline PreparedCase prepare_synthetic_case(const QualityCase& c) {
  synth::SynthOptions o = quality_case_options(c);
  if (c.kind == "field") {
    // The cameras do not depend on the degradation: the footprint first.
    synth::SynthOptions probe = o;
    probe.degradations = {synth::parse_degradation("noise:0:0.1")};
    const synth::SynthProject q = synth::make_synthetic_project(probe);
    const double fp = footprint_of(q.scene, q.truth);
    synth::Degradation d = synth::parse_degradation("field");
    d.strength = c.peak_px * fp / q.truth.bounding_box().diagonal();
    o.degradations = {d};
  }
  synth::SynthProject sp = synth::make_synthetic_project(o);
  synth::render_synthetic_views(o, &sp);
  PreparedCase p;
  p.truth = std::move(sp.truth);
  p.scene = std::move(sp.scene);
  p.error = std::move(sp.gt_error);
  p.footprint = footprint_of(p.scene, p.truth);
  return p;
}

// The PRI variants of the bench: the SPEC's settings with SSD and NCC, the
// defaults with SSD and NCC, and the offset measure (`offset` given).
inline std::map<std::string, PriOptions> quality_pri_variants(const PriOptions& offset) {
  PriOptions paper;
  paper.measure = Measure::SSD;
  paper.edge_margin = 0;
  paper.max_incidence_angle = 90;
  paper.check_interior_occlusion = false;
  std::map<std::string, PriOptions> out;
  out["paper_ssd"] = paper;
  paper.measure = Measure::NCC;
  out["paper_ncc"] = paper;
  out["default_ssd"] = PriOptions{};
  out["default_ssd"].measure = Measure::SSD;
  out["default_ncc"] = PriOptions{};
  out["default_ncc"].measure = Measure::NCC;
  out["offset"] = offset;
  return out;
}

// Every predictor on a prepared case, over the faces that every PRI variant
// observes and at least 2 views see (Smith's rule, incidence up to 85°):
// the PRI variants and the geometric predictors (views, max_angle,
// reconstructability; fewer views, a narrower angle, less
// reconstructability = predicted worse).
struct CaseScores {
  std::vector<std::size_t> faces;
  std::map<std::string, PriResult> results;
  eval::GeometricPredictors geometric;
  std::map<std::string, eval::QualityMetrics> metrics;
};
inline CaseScores score_case(const PreparedCase& p, const PriOptions& offset) {
  CaseScores out;
  for (const auto& [name, o] : quality_pri_variants(offset)) out.results[name] = compute_pri(p.scene, o);
  PriOptions smith;
  smith.max_incidence_angle = 85;
  out.geometric = eval::geometric_predictors(p.scene.mesh, select_pri_views(p.scene, smith));
  const eval::GeometricPredictors& g = out.geometric;
  for (std::size_t f = 0; f < p.scene.mesh.num_faces(); ++f) {
    bool all = g.views[f] >= 2;
    for (const auto& [name, r] : out.results) all = all && r.status[f] == FaceStatus::Observed;
    if (all) out.faces.push_back(f);
  }
  std::vector<double> error;
  for (std::size_t f : out.faces) error.push_back(p.error[f]);
  auto add = [&](const std::string& name, auto value_of) {
    std::vector<double> s;
    for (std::size_t f : out.faces) s.push_back(value_of(f));
    out.metrics[name] = eval::quality_metrics(s, error);
  };
  for (const auto& [name, r] : out.results) add(name, [&](std::size_t f) { return double(r.pri[f]); });
  add("views", [&](std::size_t f) { return -double(g.views[f]); });
  add("max_angle", [&](std::size_t f) { return -g.max_angle[f]; });
  add("reconstructability", [&](std::size_t f) { return -g.reconstructability[f]; });
  return out;
}

}  // namespace meshnbv::test
