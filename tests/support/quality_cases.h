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

#include <string>
#include <vector>

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

}  // namespace meshnbv::test
