// Suggest Next View on a synthetic building whose south facade is dented:
// PRI finds the dent, and the suggested views look at it properly.
#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"
#include "meshnbv/synth/project.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

struct Fixture {
  synth::SynthProject project;
  std::vector<float> pri;
  // The ground-truth error where PRI is defined: a perfect quality map, so
  // that the planner tests do not depend on PRI's own false positives
  // (those are measured in test_pri_quality.cpp).
  std::vector<float> oracle;
};

const Fixture& fixture() {
  static const Fixture f = [] {
    synth::SynthOptions o;
    o.scene = "building";
    o.generator.edge_length = 0.5;
    o.cameras.count = 12;
    o.cameras.layout = synth::CameraLayout::Orbit;
    o.cameras.width = 640;
    o.cameras.height = 480;
    o.render.samples_per_pixel = 1;
    synth::Degradation dent = synth::parse_degradation("dent:0.03:0.2");
    dent.center = Vec3(0, -3.45, 5);  // the south facade
    o.degradations = {dent};
    o.overwrite = true;
    Fixture out;
    out.project = synth::write_synthetic_project(o, test::temp_dir("planner"));
    out.pri = compute_pri(out.project.scene).pri;
    out.oracle = out.project.gt_error;
    for (std::size_t f = 0; f < out.pri.size(); ++f)
      if (std::isnan(out.pri[f])) out.oracle[f] = std::numeric_limits<float>::quiet_NaN();
    return out;
  }();
  return f;
}

bool safe_pose(const Scene& scene, const PinholeCamera& cam, double share) {
  const RayCaster caster(scene.mesh);
  const SafetyChecker safety(scene.mesh, caster, share * scene.mesh.bounding_box().diagonal());
  return safety.safe(cam.center());
}

}  // namespace

TEST(Planner, WorstRegionIsTheDent) {
  const Fixture& f = fixture();
  const WorstRegion r = worst_region(f.project.scene.mesh, f.pri, 10);
  // The dent is on the south facade (y = -3.45): the worst region faces south.
  EXPECT_LT(r.mean_normal.y(), -0.5) << r.mean_normal.transpose();
  int in_dent = 0;
  for (int face : r.faces) in_dent += f.project.gt_error[std::size_t(face)] > 0.05;
  EXPECT_GE(in_dent, 7) << "of the 10 worst faces";
}

TEST(Planner, TopSuggestionSeesTheRegionWithParallax) {
  const Fixture& f = fixture();
  SuggestOptions o;
  const SuggestResult r = suggest_views(f.project.scene, f.oracle, o);
  ASSERT_EQ(r.suggestions.size(), 1u);
  const Suggestion& s = r.suggestions[0];
  const WorstRegion& region = r.regions[0];
  // Every worst vertex unoccluded, inside the image.
  const RayCaster caster(f.project.scene.mesh);
  std::vector<Vec3> existing;
  for (const auto& v : f.project.scene.views) existing.push_back(v.camera.center());
  const EnergyEvaluator e(f.project.scene.mesh, caster, region, existing, o.energy);
  EXPECT_TRUE(e.sees_all_vertices(s.camera));
  EXPECT_EQ(s.seen_faces.size(), region.faces.size());
  // Parallax satisfied against every existing camera for every worst vertex.
  for (int v : region.vertices)
    for (const Vec3& c : existing) {
      const Vec3& p = f.project.scene.mesh.vertices[std::size_t(v)];
      EXPECT_GT((s.camera.center() - c).norm() / (s.camera.center() - p).norm(), o.energy.parallax_delta);
    }
  // Every term reported, and they add up.
  EXPECT_NEAR(s.energy.total, s.energy.occlusion + s.energy.focus + s.energy.parallax + s.energy.incidence, 1e-9);
  EXPECT_NEAR(s.energy.total, e.evaluate(s.camera).total, 1e-9);
  EXPECT_EQ(s.label, "nbv_1");
  EXPECT_TRUE(safe_pose(f.project.scene, s.camera, o.safety_distance));
  EXPECT_EQ(r.candidates_generated, 512u * 3u);
  EXPECT_EQ(r.candidates_evaluated + r.rejected_inside + r.rejected_too_close, r.candidates_generated);
}

TEST(Planner, SampledAndRefinedRespectSafetyAndRefinedIsNoWorse) {
  const Fixture& f = fixture();
  SuggestOptions o;
  o.top = 3;
  o.safety_distance = 0.2;  // a large margin ...
  o.sampling.distance_factors = {0.05, 0.75, 1.0};  // ... and poses close in, so the rule binds
  const SuggestResult sampled = suggest_views(f.project.scene, f.oracle, o);
  o.mode = CandidateMode::Refined;
  o.refine_best = 4;
  const SuggestResult refined = suggest_views(f.project.scene, f.oracle, o);
  ASSERT_EQ(sampled.suggestions.size(), 3u);
  ASSERT_EQ(refined.suggestions.size(), 3u);
  for (const auto* r : {&sampled, &refined})
    for (const auto& s : r->suggestions) EXPECT_TRUE(safe_pose(f.project.scene, s.camera, 0.2)) << s.label;
  for (const auto& c : sampled.ranking) EXPECT_TRUE(safe_pose(f.project.scene, c.camera, 0.2));
  EXPECT_GT(sampled.rejected_too_close, 0u);
  // The first pick starts from the same sampled set: refinement only improves it.
  EXPECT_GE(refined.suggestions[0].energy.total, sampled.suggestions[0].energy.total - 1e-9);
}

TEST(Planner, SameSeedSameSuggestions) {
  const Fixture& f = fixture();
  SuggestOptions o;
  o.top = 2;
  const SuggestResult a = suggest_views(f.project.scene, f.oracle, o);
  const SuggestResult b = suggest_views(f.project.scene, f.oracle, o);
  ASSERT_EQ(a.suggestions.size(), b.suggestions.size());
  for (std::size_t i = 0; i < a.suggestions.size(); ++i) {
    EXPECT_EQ(a.suggestions[i].camera.R, b.suggestions[i].camera.R);
    EXPECT_EQ(a.suggestions[i].camera.t, b.suggestions[i].camera.t);
  }
  o.sampling.seed = 99;
  const SuggestResult c = suggest_views(f.project.scene, f.oracle, o);
  EXPECT_NE(c.suggestions[0].camera.t, a.suggestions[0].camera.t);
}

TEST(Planner, BatchTreatsEarlierPicksAsExisting) {
  const Fixture& f = fixture();
  SuggestOptions o;
  o.top = 4;
  const SuggestResult r = suggest_views(f.project.scene, f.oracle, o);
  ASSERT_EQ(r.suggestions.size(), 4u);
  // Later picks keep parallax with the earlier ones: no two picks share a
  // centre closer than delta times their distance to the region.
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      const Vec3 a = r.suggestions[i].camera.center(), b = r.suggestions[j].camera.center();
      const double h = (b - r.regions[std::size_t(r.suggestions[j].region)].centroid).norm();
      EXPECT_GT((a - b).norm() / h, 0.25) << i << " " << j;
    }
  // A region whose faces were all seen gives way to the next one.
  if (r.regions.size() > 1) {
    for (int face : r.regions[1].faces)
      for (int old : r.regions[0].faces) EXPECT_NE(face, old);
  }
}

TEST(Planner, GivenModeRanksEveryCandidate) {
  const Fixture& f = fixture();
  Scene scene = f.project.scene;
  // Keep 3 views; the other 9 become candidates (the paper's experiment).
  for (std::size_t i = 3; i < scene.views.size(); ++i) scene.views[i].used = false;
  SuggestOptions o;
  o.mode = CandidateMode::Given;
  o.top = 2;
  const SuggestResult r = suggest_views(scene, f.oracle, o);
  ASSERT_EQ(r.ranking.size(), 9u);
  for (std::size_t i = 1; i < r.ranking.size(); ++i)
    EXPECT_GE(r.ranking[i - 1].energy.total, r.ranking[i].energy.total);
  EXPECT_EQ(r.suggestions[0].source, r.ranking[0].label);
  EXPECT_NE(r.suggestions[1].source, r.suggestions[0].source);
}

TEST(Planner, BadInput) {
  const Fixture& f = fixture();
  SuggestOptions o;
  std::vector<float> none(f.pri.size(), std::numeric_limits<float>::quiet_NaN());
  MESHNBV_EXPECT_ERROR_CONTAINS(suggest_views(f.project.scene, none, o), "no observed face");
  SuggestOptions far = o;
  far.safety_distance = 10.0;  // ten diagonals: nothing sampled can be that far
  MESHNBV_EXPECT_ERROR_CONTAINS(suggest_views(f.project.scene, f.oracle, far), "no candidate left");
  SuggestOptions given = o;
  given.mode = CandidateMode::Given;
  MESHNBV_EXPECT_ERROR_CONTAINS(suggest_views(f.project.scene, f.oracle, given), "no candidate views");
  SuggestOptions bad = o;
  bad.worst_k = 0;
  MESHNBV_EXPECT_ERROR_CONTAINS(suggest_views(f.project.scene, f.oracle, bad), "worst_k");
}
