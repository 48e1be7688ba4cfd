// PRI on JPEG photos decoded smaller (max_image_reduction): which views
// are reduced, by the lattice spacing rule written out here, and that PRI
// then reads exactly what a photo shrunk beforehand with its camera scaled
// would give.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/pri.h"
#include "meshnbv/synth/generators.h"
#include "plane_scene.h"
#include "test_util.h"

using namespace meshnbv;

namespace pri_reduction_test {

constexpr double kFocal = 720, kHeight = 5;  // plane_scene at scale 4: 800x600 photos

// A 4 m plane of 2 m faces (8 right isosceles triangles) photographed
// straight down by cameras with parallel axes at `eyes`; photos as `ext`
// files (".jpg" or ".png").
Scene down_scene(const std::string& name, const std::string& ext, const std::vector<Vec3>& eyes) {
  test::PlaneSceneOptions o;
  o.edge = 2.0;
  o.scale = kFocal / 180;
  o.look_down = true;
  o.extension = ext;
  return test::plane_scene(name, test::kPlaneNoise, eyes, o);
}

// Eyes apart along x only, so that the plane stays inside every photo.
const std::vector<Vec3> kNear = {{0, 0, kHeight}, {0.5, 0, kHeight}, {-0.5, 0, kHeight}, {0.25, 0, kHeight}};

// The rule for a face whose legs project to L pixels in every view that
// sees it: lattice rows (least height) / r apart, r = min(32, ceil(longest
// edge)), the lattice contracted by keep = 1 - edge_margin / inner (inner:
// a third of its least height, in the view that sees it smallest); the
// reduction the largest power of two up to `max` and to that spacing.
int expected_reduction(double legs, double smallest_legs, int max, int samples_per_side = 0,
                       double edge_margin = 0.5) {
  const double height = legs / std::sqrt(2.0);
  const double longest = std::max(legs, smallest_legs) * std::sqrt(2.0);
  const double r = samples_per_side > 0 ? samples_per_side : std::min(32.0, std::ceil(longest));
  const double inner = smallest_legs / std::sqrt(2.0) / 3.0;
  const double spacing = (1.0 - edge_margin / inner) * height / r;
  int k = 1;
  while (2 * k <= max && 2 * k <= spacing) k *= 2;
  return k;
}

}  // namespace pri_reduction_test

using namespace pri_reduction_test;

TEST(PriReduction, ViewsReducedByTheirLatticeSpacing) {
  std::vector<Vec3> eyes = kNear;
  eyes.push_back({0, 0, 12});  // farther: the faces' legs 120 px there
  const Scene scene = down_scene("pri_reduction_rule", ".jpg", eyes);
  const double near_legs = 2 * kFocal / kHeight,
               far_legs = 2 * kFocal / 12;  // 288, 120 px
  ASSERT_EQ(expected_reduction(near_legs, far_legs, 8),
            4);  // the case this test is about
  ASSERT_EQ(expected_reduction(far_legs, far_legs, 8), 2);
  const auto reductions = [&](const PriOptions& o) { return select_pri_views(scene, o).reductions; };
  for (int max : {1, 2, 3, 4, 8}) {
    PriOptions o;
    o.max_image_reduction = max;
    const std::vector<int> r = reductions(o);
    ASSERT_EQ(r.size(), eyes.size());
    for (std::size_t i = 0; i < kNear.size(); ++i)
      EXPECT_EQ(r[i], expected_reduction(near_legs, far_legs, max)) << max;
    EXPECT_EQ(r.back(), expected_reduction(far_legs, far_legs, max)) << max;
  }
  PriOptions most;  // whatever the default, the most reduction allowed
  most.max_image_reduction = 8;
  PriOptions dense = most;
  dense.samples_per_side = 64;
  EXPECT_EQ(reductions(dense)[0], expected_reduction(near_legs, far_legs, 8, 64));
  EXPECT_EQ(reductions(dense)[0], 2);
  PriOptions no_margin = most;
  no_margin.edge_margin = 0;
  EXPECT_EQ(reductions(no_margin)[0], expected_reduction(near_legs, far_legs, 8, 0, 0));
  // A tile's selection has the whole mesh's reductions (tiles and ranks agree).
  EXPECT_EQ(select_pri_views(scene, most, {}, {1, 4}).reductions, reductions(most));
  // Small faces in the photo: every view whole.
  Scene fine = scene;
  fine.mesh = synth::make_ground(Vec3(-2, -2, 0), Vec3(2, 2, 0), 0.25, 0);
  fine.mesh.face_attributes.clear();
  EXPECT_EQ(select_pri_views(fine, most).reductions, std::vector<int>(eyes.size(), 1));
}

TEST(PriReduction, OnlyJpegFilesAreReduced) {
  Scene png = down_scene("pri_reduction_png", ".png", kNear);
  PriOptions most;
  most.max_image_reduction = 8;
  EXPECT_EQ(select_pri_views(png, most).reductions, std::vector<int>(kNear.size(), 1));
  // In memory: whole too.
  for (auto& v : png.views) {
    v.pixels = std::make_shared<const Image>(Image::load(v.image_path));
    v.image_path.clear();
  }
  EXPECT_EQ(select_pri_views(png, most).reductions, std::vector<int>(kNear.size(), 1));
  const PriResult r = compute_pri(png, most);
  EXPECT_EQ(r.views_reduced, 0u);
}

// PRI on reduced JPEGs equals PRI on those reduced photos saved whole, with
// each camera scaled by the documented map x' = (x + 0.5) / k - 0.5
// (fx / k, cx' = (cx + 0.5) / k - 0.5, size rounded up): the sampling
// reads the reduced photo exactly where the full-size projection falls.
TEST(PriReduction, ReadsTheReducedPhotoWhereTheProjectionFalls) {
  Scene scene = down_scene("pri_reduction_map", ".jpg", kNear);
  for (auto& v : scene.mesh.vertices) v.z() += 0.05 * std::sin(3 * v.x() + 2 * v.y());  // some error
  PriOptions o;
  o.max_image_reduction = 8;
  o.edge_margin = 0;  // in pixels, so it would differ between the two scenes
  const PriViewSelection sel = select_pri_views(scene, o);
  ASSERT_EQ(sel.reductions[0], 4);
  const PriResult reduced = compute_pri(scene, o);
  EXPECT_EQ(reduced.views_reduced, kNear.size());

  Scene shrunk = scene;
  const std::string dir = test::temp_dir("pri_reduction_map_shrunk");
  for (std::size_t i = 0; i < shrunk.views.size(); ++i) {
    View& v = shrunk.views[i];
    const int k = sel.reductions[i];
    const Image small = Image::load(v.image_path, ImageOrientation::stored, k);
    ASSERT_EQ(small.reduction(), k);
    v.image_path = dir + "/" + v.label + ".png";
    small.save(v.image_path);
    PinholeCamera& c = v.camera;
    c.fx /= k, c.fy /= k;
    c.cx = (c.cx + 0.5) / k - 0.5, c.cy = (c.cy + 0.5) / k - 0.5;
    c.width = (c.width + k - 1) / k, c.height = (c.height + k - 1) / k;
  }
  const PriResult expected = compute_pri(shrunk, o);
  ASSERT_EQ(expected.pri.size(), reduced.pri.size());
  std::size_t compared = 0;
  for (std::size_t f = 0; f < reduced.pri.size(); ++f) {
    ASSERT_EQ(std::isnan(reduced.pri[f]), std::isnan(expected.pri[f])) << f;
    if (std::isnan(reduced.pri[f])) continue;
    EXPECT_EQ(reduced.pri_samples[f], expected.pri_samples[f]) << f;
    EXPECT_NEAR(reduced.pri[f], expected.pri[f], 1e-4 * expected.pri[f] + 1e-9) << f;
    ++compared;
  }
  EXPECT_EQ(compared, scene.mesh.num_faces());

  // The values rest on the reduction: their evidence keys say so, and the
  // whole photos' keys are those of a scene without reduction.
  PriOptions whole = o;
  whole.max_image_reduction = 1;
  const PriResult full = compute_pri(scene, whole);
  EXPECT_EQ(full.views_reduced, 0u);
  EXPECT_NE(full.evidence_key[0], reduced.evidence_key[0]);
  EXPECT_EQ(full.view_keys, reduced.view_keys);
  // And an error is still told from the truth as on the full photos: the
  // mesh raised 10 cm (1.5 px of parallax between the views 0.5 m apart)
  // against the true plane, every face of one above every face of the other.
  Scene truth = scene;
  truth.mesh = down_scene("pri_reduction_map_truth", ".png", {}).mesh;
  Scene raised = truth;
  for (auto& v : raised.mesh.vertices) v.z() += 0.1;
  for (const PriOptions& options : {o, whole}) {
    const PriResult t = compute_pri(truth, options), e = compute_pri(raised, options);
    EXPECT_EQ(t.views_reduced, options.max_image_reduction > 1 ? kNear.size() : 0u);
    const float worst_truth = *std::max_element(t.pri.begin(), t.pri.end());
    const float best_raised = *std::min_element(e.pri.begin(), e.pri.end());
    EXPECT_GT(best_raised, 3 * worst_truth) << options.max_image_reduction;
  }
}
