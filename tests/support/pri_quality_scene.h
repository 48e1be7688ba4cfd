// The scenes of the PRI quality checks, shared by the test
// (tests/core/test_pri_quality.cpp) and the bench that writes the figures
// (bench/pri_quality.cpp), so that both measure the same thing: 16 orbit
// views at 1280x960 (one sample per pixel: the textures are band-limited)
// and one degradation centred on a facade every camera ring sees.
#pragma once

#include <string>

#include "meshnbv/synth/project.h"

namespace meshnbv::test {

inline synth::SynthOptions pri_quality_options(const std::string& scene,
                                               const std::string& degradation) {
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
  return o;
}

}  // namespace meshnbv::test
