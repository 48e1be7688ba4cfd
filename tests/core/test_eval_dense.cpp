// The dense backend's stereo depth against the renderer's true depth: a
// textured box seen by pairs whose baseline runs right, left, up and down
// in the reference image (the four canonical orientations of the rectified
// pair), with a distorting lens, and the fusion of a ring of views.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <fstream>

#include "meshnbv/error.h"
#include "meshnbv/eval/dense_backend.h"
#include "meshnbv/eval/metrics.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/synth/generators.h"
#include "meshnbv/texture.h"
#include "test_util.h"

namespace meshnbv::eval {
namespace {

namespace fs = std::filesystem;

struct BoxWorld {
  TriangleMesh mesh = synth::make_box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5), 0.05, 1);
  RayCaster caster{mesh};
  SolidTexture texture{1, [] {
                         std::vector<Material> m = default_materials();
                         for (auto& x : m) x.scale *= 0.2;  // 10 cm bricks on a 1 m box
                         return m;
                       }()};
  Image render(const PinholeCamera& c, std::vector<float>* depth = nullptr) const {
    return meshnbv::render({&mesh, &caster, &texture, mesh.face_attribute(synth::kMaterialAttribute)}, c, {},
                           depth);
  }
};

const BoxWorld& world() {
  static const BoxWorld w;
  return w;
}

// A camera 3 m from the box centre, at `azimuth` and `elevation` degrees,
// looking at a point slightly off the centre (so the box is not centred).
PinholeCamera camera_at(double azimuth, double elevation, int w = 480, int h = 360) {
  const double a = azimuth * M_PI / 180, e = elevation * M_PI / 180;
  const Vec3 eye(3 * std::cos(e) * std::sin(a), -3 * std::sin(e), -3 * std::cos(e) * std::cos(a));
  return PinholeCamera::look_at(eye, Vec3(0.05, 0.02, 0), Vec3(0, -1, 0), 0.9 * w, 0.9 * w, (w - 1) / 2.0,
                                (h - 1) / 2.0, w, h);
}

struct DepthCheck {
  double covered = 0;     // share of the box's pixels with a depth
  double within_1pc = 0;  // share of those within 1% of the true depth
  double median_error = 0;  // relative
};

DepthCheck check_depth(const PinholeCamera& ref, const PinholeCamera& other) {
  std::vector<float> truth;
  const Image a = world().render(ref, &truth);
  const Image b = world().render(other);
  const DepthMap d = stereo_depth(ref, a, other, b, 2.0, 4.0, DenseOptions{});
  EXPECT_EQ(d.width, ref.width);
  EXPECT_EQ(d.height, ref.height);
  std::size_t box = 0, got = 0, good = 0;
  std::vector<double> errors;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!std::isfinite(truth[i])) {
      EXPECT_TRUE(d.depth[i] == 0.0f || std::abs(d.depth[i] - 3) < 1.2) << "depth off the box at " << i;
      continue;
    }
    ++box;
    if (d.depth[i] <= 0) continue;
    ++got;
    const double e = std::abs(d.depth[i] - truth[i]) / truth[i];
    errors.push_back(e);
    if (e <= 0.01) ++good;
  }
  DepthCheck c;
  c.covered = double(got) / double(box);
  c.within_1pc = got ? double(good) / double(got) : 0;
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + long(errors.size() / 2), errors.end());
    c.median_error = errors[errors.size() / 2];
  }
  return c;
}

void expect_good(const DepthCheck& c, const char* what) {
  EXPECT_GT(c.covered, 0.6) << what;
  EXPECT_GT(c.within_1pc, 0.9) << what;
  EXPECT_LT(c.median_error, 0.003) << what;
}

TEST(DenseStereo, OtherViewToTheRight) { expect_good(check_depth(camera_at(0, 20), camera_at(12, 20)), "right"); }

TEST(DenseStereo, OtherViewToTheLeft) { expect_good(check_depth(camera_at(0, 20), camera_at(-12, 20)), "left"); }

// Converging views 30 degrees apart: each rectified image keeps its own
// principal point, so the object stays in both frames.
TEST(DenseStereo, WideBaseline) { expect_good(check_depth(camera_at(0, 20), camera_at(30, 20)), "30 degrees"); }

TEST(DenseStereo, OtherViewAboveAndBelow) {
  expect_good(check_depth(camera_at(0, 20), camera_at(0, 32)), "above");
  expect_good(check_depth(camera_at(0, 20), camera_at(0, 8)), "below");
}

TEST(DenseStereo, DistortingLens) {
  PinholeCamera ref = camera_at(0, 20), other = camera_at(12, 20);
  ref.k1 = -0.15;
  ref.k2 = 0.03;
  other.k1 = 0.1;
  other.p1 = 0.002;
  expect_good(check_depth(ref, other), "lens");
}

TEST(DenseStereo, SameCentreIsAnError) {
  const PinholeCamera ref = camera_at(0, 20);
  PinholeCamera turned = ref;
  turned.R = Eigen::AngleAxisd(0.1, Vec3::UnitY()).toRotationMatrix() * ref.R;
  turned.set_center(ref.center());
  const Image a = world().render(ref);
  EXPECT_THROW(stereo_depth(ref, a, turned, a, 2, 4, {}), Error);
  EXPECT_THROW(stereo_depth(ref, a, camera_at(12, 20), a, 4, 2, {}), Error);
}

TEST(DenseStereo, CachedDisparityGivesTheSameDepth) {
  const fs::path dir = fs::temp_directory_path() / "meshnbv_dense_cache_test";
  fs::remove_all(dir);
  const PinholeCamera ref = camera_at(0, 20), other = camera_at(12, 20);
  const Image a = world().render(ref), b = world().render(other);
  const std::string png = (dir / "pair.png").string();
  const DepthMap first = stereo_depth(ref, a, other, b, 2, 4, {}, png);
  ASSERT_TRUE(fs::exists(png));
  const DepthMap again = stereo_depth(ref, Image(), other, Image(), 2, 4, {}, png);
  EXPECT_EQ(first.depth, again.depth);
  // A damaged entry is not read: without images it cannot be matched again.
  { std::ofstream(png) << "not a png"; }
  EXPECT_THROW(stereo_depth(ref, Image(), other, Image(), 2, 4, {}, png), Error);
  fs::remove_all(dir);
}

// Eight views on a ring (45 degrees apart would be too wide: 20 degrees),
// sparse points from the truth, fused dense points near the surface.
TEST(DensePoints, RingOfViewsFusesPointsOnTheSurface) {
  const fs::path dir = fs::temp_directory_path() / "meshnbv_dense_points_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<View> views;
  for (int k = 0; k < 6; ++k) {
    View v;
    v.label = "v" + std::to_string(k);
    v.camera = camera_at(20.0 * k, 20);
    v.image_path = (dir / (v.label + ".png")).string();
    world().render(v.camera).save(v.image_path);
    views.push_back(v);
  }
  // Sparse points: box surface samples seen by the cameras they face (the
  // box is convex: facing is seeing).
  std::vector<SparsePoint> sparse;
  for (const Vec3& p : sample_surface(world().mesh, 0.05, 3)) {
    SparsePoint s;
    s.position = p;
    int axis = 0;
    p.cwiseAbs().maxCoeff(&axis);
    const Vec3 normal = Vec3::Unit(axis) * (p(axis) > 0 ? 1.0 : -1.0);
    for (std::size_t c = 0; c < views.size(); ++c)
      if (normal.dot(views[c].camera.center() - p) > 0) s.views.push_back(int(c));
    if (s.views.size() >= 2) sparse.push_back(s);
  }
  std::vector<int> selected = {0, 1, 2, 3, 4, 5};
  DenseStats stats;
  DenseOptions o;
  o.max_points = 20000;
  const auto points = dense_points(views, selected, sparse, (dir / "cache").string(), o, &stats);
  EXPECT_EQ(stats.views, 6u);
  EXPECT_GE(stats.pairs, 10u);
  EXPECT_EQ(stats.pairs_computed, stats.pairs);
  EXPECT_TRUE(stats.failures.empty()) << stats.failures.front();
  EXPECT_LE(points.size(), 20000u);
  EXPECT_GT(points.size(), 5000u);
  std::size_t near = 0;
  for (const auto& p : points) {
    EXPECT_GE(p.views.size(), 3u);  // the reference and two agreeing partners
    // Two pixel footprints (3 m / 432 px = 7 mm each).
    if (world().caster.closest_point(p.position) < 0.014) ++near;
  }
  EXPECT_GT(double(near) / double(points.size()), 0.95);
  // Again: every pair from the cache, the same points.
  DenseStats again;
  const auto cached = dense_points(views, selected, sparse, (dir / "cache").string(), o, &again);
  EXPECT_EQ(again.pairs_computed, 0u);
  ASSERT_EQ(cached.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(cached[i].position, points[i].position);
  // A view without sparse points is listed as failed; the others go on.
  std::vector<SparsePoint> fewer = sparse;
  for (auto& s : fewer) s.views.erase(std::remove(s.views.begin(), s.views.end(), 5), s.views.end());
  DenseStats partial;
  dense_points(views, selected, fewer, (dir / "cache").string(), o, &partial);
  EXPECT_EQ(partial.views, 5u);
  ASSERT_FALSE(partial.failures.empty());
  EXPECT_NE(partial.failures.front().find("v5"), std::string::npos) << partial.failures.front();
  fs::remove_all(dir);
}

TEST(DenseOptions, RangesAreChecked) {
  DenseOptions o;
  o.block_size = 4;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.min_agreeing = 5;  // more than the partners
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.max_angle = 2;  // below min_angle
  EXPECT_THROW(o.check(), Error);
  EXPECT_EQ(parse_backend("dense"), BackendKind::Dense);
  EXPECT_THROW(parse_backend("mvs"), Error);
}

}  // namespace
}  // namespace meshnbv::eval
