// What each face's PRI rests on (PriResult's evidence: pairs, samples,
// texture) and how the front ends' shared outputs carry it: the PLY of
// mesh_with_pri, the JSON summary and pri_evidence().
// Scene: a 4 m x 4 m plane z = 0 (faces of 0.5 m) under 2 or 4 cameras 5 m
// above it, 200x150 images, rendered with a noise texture or a flat colour.
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/pri_io.h"
#include "meshnbv/pri.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/results.h"
#include "meshnbv/synth/generators.h"
#include "plane_scene.h"
#include "test_util.h"

using namespace meshnbv;
using test::kPlaneEyes;
using test::kPlaneNoise;

namespace {

const Material kFlat = {Pattern::Noise, Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5), 1.0, 0.0};
Scene plane_scene(const std::string& name, const Material& material, const std::vector<Vec3>& eyes) {
  return test::plane_scene("pri_evidence_" + name, material, eyes);
}

// Faces away from the plane's border (the border's samples see the sky).
bool interior(const Scene& s, std::size_t f) {
  const Vec3 c = s.mesh.face_centroid(f);
  return std::abs(c.x()) < 1.4 && std::abs(c.y()) < 1.4;
}

PriOptions with(Measure m, int samples_per_side) {
  PriOptions o;
  o.measure = m;
  o.samples_per_side = samples_per_side;
  return o;
}

}  // namespace

// ssd and ncc average every pair of the n views: n (n - 1) / 2; each view
// reads the whole lattice, (r + 1)(r + 2) / 2 samples.
TEST(PriEvidence, PairsAndSamplesOfSsdAndNcc) {
  const Scene s = plane_scene("pairs", kPlaneNoise, kPlaneEyes);
  for (Measure m : {Measure::SSD, Measure::NCC}) {
    const PriResult r = compute_pri(s, with(m, 3));
    std::size_t four = 0, low = 0;
    for (std::size_t f = 0; f < r.pri.size(); ++f) {
      ASSERT_FALSE(std::isnan(r.pri[f])) << measure_name(m) << " face " << f;
      const int n = r.pri_views[f];
      EXPECT_EQ(r.pri_samples[f], 10) << f;  // r = 3
      EXPECT_EQ(r.pri_pairs[f], n * (n - 1) / 2) << measure_name(m) << " face " << f;
      EXPECT_GT(r.pri_texture[f], 0.0f) << f;
      four += n == 4;
      low += r.pri_texture[f] < kLowTexture;
    }
    EXPECT_GT(four, r.pri.size() / 2) << measure_name(m);  // most faces: all four views, 6 pairs
    EXPECT_EQ(pri_evidence(r).low_texture, low);
    EXPECT_LT(low, r.pri.size() / 20);  // the noise texture: a few faces at most
  }
}

// offset compares the n - 1 other views with the reference view.
TEST(PriEvidence, PairsAndSamplesOfOffset) {
  const Scene s = plane_scene("offset", kPlaneNoise, kPlaneEyes);
  const PriResult r = compute_pri(s, with(Measure::Offset, 4));
  std::size_t four = 0;
  for (std::size_t f = 0; f < r.pri.size(); ++f) {
    ASSERT_FALSE(std::isnan(r.pri[f])) << f;
    EXPECT_EQ(r.pri_samples[f], 15) << f;  // r = 4
    EXPECT_EQ(r.pri_pairs[f], r.pri_views[f] - 1) << f;
    four += r.pri_views[f] == 4;
  }
  EXPECT_GT(four, r.pri.size() / 2);
}

// A constant image has no texture: 0 under ssd (the faces are observed, PRI
// 0), and offset has nothing to compare (textureless, 0 pairs).
TEST(PriEvidence, ConstantImagesHaveNoTexture) {
  const Scene s = plane_scene("flat", kFlat, kPlaneEyes);
  const PriResult ssd = compute_pri(s, with(Measure::SSD, 3));
  const PriResult offset = compute_pri(s, with(Measure::Offset, 3));
  std::size_t inner = 0;
  for (std::size_t f = 0; f < ssd.pri.size(); ++f) {
    if (!interior(s, f)) continue;
    ++inner;
    EXPECT_EQ(ssd.status[f], FaceStatus::Observed) << f;
    EXPECT_NEAR(ssd.pri_texture[f], 0.0, 1e-6) << f;
    EXPECT_EQ(offset.status[f], FaceStatus::Textureless) << f;
    EXPECT_EQ(offset.pri_pairs[f], 0) << f;
    EXPECT_NEAR(offset.pri_texture[f], 0.0, 1e-6) << f;
  }
  EXPECT_GT(inner, 50u);
  const PriEvidence e = pri_evidence(ssd);
  EXPECT_EQ(e.observed, ssd.observed);
  EXPECT_GE(e.low_texture, inner);
}

// Two cameras: every observed face rests on 2 views and 1 pair.
TEST(PriEvidence, TwoViewsAreCounted) {
  const Scene s = plane_scene("two", kPlaneNoise, {kPlaneEyes[0], kPlaneEyes[1]});
  const PriResult r = compute_pri(s, with(Measure::SSD, 3));
  const PriEvidence e = pri_evidence(r);
  EXPECT_GT(e.observed, 50u);
  EXPECT_EQ(e.two_views, e.observed);
  EXPECT_LT(e.low_texture, e.observed / 20);  // the noise texture: a few faces at most
  ASSERT_EQ(e.pairs_percentiles.size(), 7u);
  EXPECT_EQ(e.pairs_percentiles.front().second, 1.0);
  EXPECT_EQ(e.pairs_percentiles.back().second, 1.0);
}

// pri_evidence on a result written by hand: exact counts and percentiles.
TEST(PriEvidence, CountsAndPercentilesByHand) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  PriResult r;
  r.pri = {0.1f, 0.2f, nan, 0.3f, 0.4f};
  r.pri_views = {2, 3, 1, 2, 4};
  r.pri_pairs = {1, 3, 0, 1, 6};
  r.pri_samples = {10, 10, 10, 15, 21};
  r.pri_texture = {0.005f, 0.02f, nan, 0.04f, 0.0f};
  r.status.assign(5, FaceStatus::Observed);
  r.status[2] = FaceStatus::Unobserved;
  const PriEvidence e = pri_evidence(r);
  EXPECT_EQ(e.observed, 4u);
  EXPECT_EQ(e.two_views, 2u);
  EXPECT_EQ(e.low_texture, 2u);  // 0.005 and 0 are below 0.01
  EXPECT_EQ(pri_evidence(r, 0.03).low_texture, 3u);
  ASSERT_EQ(e.texture_percentiles.size(), 7u);
  EXPECT_NEAR(e.texture_percentiles[3].second, 0.0125, 1e-7);  // median of 0 0.005 0.02 0.04
  EXPECT_NEAR(e.texture_percentiles.back().second, 0.04, 1e-7);
  EXPECT_EQ(e.pairs_percentiles[3].second, 2.0);   // median of 1 1 3 6
  EXPECT_EQ(e.samples_percentiles[0].second, 10.0);
  EXPECT_EQ(e.samples_percentiles.back().second, 21.0);
  r.pri_texture.pop_back();
  MESHNBV_EXPECT_ERROR_CONTAINS(pri_evidence(r), "5 faces but 5 views, 5 pairs, 5 samples and 4 texture");
  MESHNBV_EXPECT_ERROR_CONTAINS(mesh_with_pri(TriangleMesh{}, r), "texture values");
}

TEST(PriEvidence, MeasureUnits) {
  EXPECT_EQ(measure_unit(Measure::SSD), "squared intensity");
  EXPECT_EQ(measure_unit(Measure::NCC), "1 - rho over 2");
  EXPECT_EQ(measure_unit(Measure::Offset), "scene units");
}

// The PLY carries the evidence beside quality and pri_views, reads back
// exactly, and read_pri_for_mesh still takes the PRI from it.
TEST(PriEvidence, PlyHoldsTheEvidence) {
  const Scene s = plane_scene("ply", kPlaneNoise, kPlaneEyes);
  const PriResult r = compute_pri(s, with(Measure::Offset, 3));
  const std::string dir = test::temp_dir("PriEvidence.Ply");
  io::write_ply(mesh_with_pri(s.mesh, r), dir + "/pri.ply");
  const TriangleMesh back = io::read_ply(dir + "/pri.ply");
  for (const char* name : {"quality", "pri_views", "pri_pairs", "pri_samples", "pri_texture"})
    ASSERT_NE(back.face_attribute(name), nullptr) << name;
  const std::vector<float>& pairs = *back.face_attribute("pri_pairs");
  const std::vector<float>& samples = *back.face_attribute("pri_samples");
  const std::vector<float>& texture = *back.face_attribute("pri_texture");
  ASSERT_EQ(pairs.size(), r.pri.size());
  for (std::size_t f = 0; f < r.pri.size(); ++f) {
    EXPECT_EQ(pairs[f], float(r.pri_pairs[f])) << f;
    EXPECT_EQ(samples[f], float(r.pri_samples[f])) << f;
    EXPECT_EQ(texture[f], r.pri_texture[f]) << f;
  }
  const std::vector<float> pri = io::read_pri_for_mesh(dir + "/pri.ply", s.mesh);
  ASSERT_EQ(pri.size(), r.pri.size());
  for (std::size_t f = 0; f < pri.size(); ++f) EXPECT_EQ(pri[f], r.pri[f]) << f;
}

// The JSON summary names the measure and its unit, and its evidence block
// and worst faces agree with the result.
TEST(PriEvidence, SummaryJson) {
  const Scene s = plane_scene("json", kPlaneNoise, kPlaneEyes);
  const PriOptions o = with(Measure::Offset, 3);
  const PriResult r = compute_pri(s, o);
  const nlohmann::json j = nlohmann::json::parse(pri_summary_json(r, o, 5));
  EXPECT_EQ(j["measure"], "offset");
  EXPECT_EQ(j["unit"], "scene units");
  EXPECT_EQ(j["options"]["measure"], "offset");
  const PriEvidence e = pri_evidence(r);
  const auto& ev = j["evidence"];
  EXPECT_EQ(ev["observed"], r.observed);
  EXPECT_EQ(ev["two_views"], e.two_views);
  EXPECT_EQ(ev["low_texture"], e.low_texture);
  EXPECT_EQ(ev["low_texture_below"], kLowTexture);
  EXPECT_EQ(ev["samples_percentiles"]["p50"], 10.0);
  EXPECT_EQ(ev["pairs_percentiles"]["p100"], 3.0);  // 4 views - 1
  EXPECT_NEAR(double(ev["texture_percentiles"]["p50"]), e.texture_percentiles[3].second, 1e-12);
  ASSERT_EQ(j["worst_faces"].size(), 5u);
  for (const auto& w : j["worst_faces"]) {
    const auto f = std::size_t(w["face"].get<int>());
    EXPECT_EQ(w["pairs"], r.pri_pairs[f]);
    EXPECT_NEAR(double(w["texture"]), r.pri_texture[f], 1e-7);
    EXPECT_EQ(w["pairs"].get<int>(), w["views"].get<int>() - 1);
  }
  const nlohmann::json ssd = nlohmann::json::parse(pri_summary_json(r, with(Measure::SSD, 3)));
  EXPECT_EQ(ssd["measure"], "ssd");
  EXPECT_EQ(ssd["unit"], "squared intensity");
}
