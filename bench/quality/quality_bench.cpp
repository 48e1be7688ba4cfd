// The ground-truth bench of quality indices (issue #14): every predictor of
// a face's error side by side on the same cases, in one run.
//
//   quality_bench [--out FILE.json] [--cache DIR] [--only NAME]...
//
// Cases (tests/support/quality_cases.h): smooth whole-mesh error at 0.5, 1
// and 2 px, local damage, and real reconstructions of the synthetic scenes
// by the evaluation loop's backend (COLMAP, needs `colmap` on the PATH).
// Predictors: PRI with the SPEC's settings (paper_ssd, paper_ncc), today's
// defaults with SSD and NCC (default_ssd, default_ncc), the offset measure
// (offset), and the geometric ones (views, max_angle, reconstructability;
// meshnbv/eval/quality.h). Each on the faces that every PRI predictor
// observes; true error: mean distance of the face's samples to the truth.
// bench/quality/run.sh runs it and writes bench/results/quality/.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshnbv/eval/loop.h"
#include "meshnbv/eval/quality.h"
#include "meshnbv/options.h"
#include "meshnbv/pri.h"
#include "meshnbv/synth/project.h"
#include "quality_cases.h"

using namespace meshnbv;
using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A case ready to score, with what the bench reports of its preparation.
struct Prepared : test::PreparedCase {
  json info;
};

Prepared prepare_recon(const test::QualityCase& c, const std::string& cache) {
  synth::SynthOptions o = test::quality_case_options(c);
  o.degradations = {synth::parse_degradation("noise:0:0.1")};
  o.overwrite = true;
  const fs::path dir = fs::path(cache) / c.name;
  if (!fs::exists(dir / "project" / "scene.json")) synth::write_synthetic_project(o, (dir / "project").string());
  const eval::Dataset d = eval::load_dataset((dir / "project").string(), (dir / "loop").string());
  const eval::ColmapWorkspace ws((dir / "colmap").string(), d.views);
  std::vector<int> all(d.views.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  eval::LoopOptions lo;
  fs::create_directories(dir / "work");
  const eval::Reconstruction r = eval::reconstruct(ws, all, (dir / "work").string(), lo, (dir / "loop").string());
  Prepared p;
  p.truth = d.truth;
  p.scene.mesh = r.mesh;
  p.scene.views = d.views;
  p.error = synth::face_distance_to_surface(r.mesh, d.truth);
  p.footprint = test::footprint_of(p.scene, p.truth);
  p.info["sparse_points"] = r.sparse.points.size();
  return p;
}

json metrics_json(const eval::QualityMetrics& m) {
  return {{"spearman", m.spearman}, {"auc", m.auc}, {"precision_at_10", m.precision_at_10},
          {"precision_at_100", m.precision_at_100}};
}

json run_case(const test::QualityCase& c, Prepared& p) {
  json row = {{"name", c.name}, {"kind", c.kind}, {"scene", c.scene}, {"faces", p.scene.mesh.num_faces()},
              {"footprint_m_per_px", p.footprint}};
  if (!p.info.is_null()) row.update(p.info);
  PriOptions offset;
  offset.measure = Measure::Offset;
  // Experiments: MESHNBV_OFFSET_OPTIONS='{"support_radius": 4}' (JSON of the option table).
  if (const char* j = std::getenv("MESHNBV_OFFSET_OPTIONS")) parse_options_json(j, pri_option_table(), &offset);
  const test::CaseScores scores = test::score_case(p, offset);
  const std::vector<std::size_t>& faces = scores.faces;
  const std::map<std::string, PriResult>& results = scores.results;
  json seconds;
  for (const auto& [name, r] : results) seconds[name] = r.seconds;
  std::vector<double> err_px;
  for (std::size_t f : faces) err_px.push_back(p.error[f] / p.footprint);
  row["observed_faces"] = faces.size();
  std::sort(err_px.begin(), err_px.end());
  if (!err_px.empty())
    row["error_px"] = {{"p50", err_px[err_px.size() / 2]}, {"p90", err_px[err_px.size() * 9 / 10]},
                       {"max", err_px.back()}};
  json pred;
  for (const auto& [name, m] : scores.metrics) pred[name] = metrics_json(m);
  row["predictors"] = pred;
  if (const char* dump = std::getenv("MESHNBV_QUALITY_DUMP")) {  // per-face CSV, for analysis
    std::ofstream csv(std::string(dump) + "_" + c.name + ".csv");
    csv << "face,error";
    for (const auto& [name, r] : results) csv << "," << name;
    csv << ",views,pairs,texture,offset_signed,offset_precision,offset_pixel,offset_steady,cx,cy,cz,nx,ny,nz\n";
    const PriResult& off = results.at("offset");
    for (std::size_t f : faces) {
      csv << f << "," << p.error[f];
      for (const auto& [name, r] : results) csv << "," << r.pri[f];
      const Vec3 cc = p.scene.mesh.face_centroid(f), nn = p.scene.mesh.face_normal(f);
      csv << "," << off.pri_views[f] << "," << off.pri_pairs[f] << "," << off.pri_texture[f] << ","
          << off.offset_signed[f] << "," << off.offset_precision[f] << "," << off.offset_pixel[f] << "," << off.offset_steady[f]
          << "," << cc.x()
          << "," << cc.y() << "," << cc.z() << "," << nn.x() << "," << nn.y() << "," << nn.z() << "\n";
    }
  }
  row["pri_seconds"] = seconds;
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "bench/results/quality/quality.json", cache = "/tmp/meshnbv_quality_cache";
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--cache" && i + 1 < argc) cache = argv[++i];
    else if (a == "--only" && i + 1 < argc) only.push_back(argv[++i]);
    else {
      std::cerr << "usage: quality_bench [--out FILE] [--cache DIR] [--only NAME]...\n";
      return 2;
    }
  }
  const double t0 = now_s();
  json result;
  char date[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%S+00:00", std::gmtime(&t));
  result["date"] = date;
  result["program"] = "bench/quality/quality_bench.cpp";
  result["threads"] = std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
  json rows = json::array();
  try {
    for (const auto& c : test::quality_cases()) {
      if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
      const double tc = now_s();
      Prepared p;
      if (c.kind == "recon") p = prepare_recon(c, cache);
      else static_cast<test::PreparedCase&>(p) = test::prepare_synthetic_case(c);
      json row = run_case(c, p);
      row["seconds"] = now_s() - tc;
      std::cout << row.dump() << std::endl;
      rows.push_back(row);
    }
  } catch (const std::exception& e) {
    std::cerr << "quality_bench: " << e.what() << "\n";
    return 1;
  }
  result["cases"] = rows;
  result["seconds"] = now_s() - t0;
  fs::create_directories(fs::path(out).parent_path());
  std::ofstream f(out);
  f << result.dump(1) << "\n";
  if (!f) {
    std::cerr << "cannot write " << out << "\n";
    return 1;
  }
  std::cout << "wrote " << out << "\n";
  return 0;
}
