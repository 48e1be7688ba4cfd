// Renderer: geometry lands where the camera model says, output is
// deterministic, and the truth is photo-consistent across views.
#include <cmath>
#include <random>

#include "meshnbv/error.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/synth/generators.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

// 20 m x 20 m plane z = 0 facing +z, material 0 = flat stripes across y with
// period 1 m: luminance steps at y = k metres.
struct StripedPlane {
  TriangleMesh mesh = synth::make_ground(Vec3(-10, -10, 0), Vec3(10, 10, 0), 2.0, 0);
  std::vector<Material> materials{{Pattern::Stripes, Vec3(0.9, 0.9, 0.9), Vec3(0.1, 0.1, 0.1), 1.0, 0.0}};
  SolidTexture texture{7, materials};
  RayCaster caster{mesh};
  RenderInputs inputs() const {
    return {&mesh, &caster, &texture, mesh.face_attribute(synth::kMaterialAttribute)};
  }
};

// Sub-pixel row where the luminance of column u crosses the mid level
// between rows v0 and v1 (exclusive), searching downwards.
double crossing_row(const Image& img, int u, int v0, int v1) {
  double lo = 1e9, hi = -1e9;
  for (int v = v0; v <= v1; ++v) {
    lo = std::min<double>(lo, img.luminance(u, v));
    hi = std::max<double>(hi, img.luminance(u, v));
  }
  const double level = 0.5 * (lo + hi);
  for (int v = v0; v < v1; ++v) {
    const double a = img.luminance(u, v), b = img.luminance(u, v + 1);
    if ((a - level) * (b - level) <= 0 && a != b) return v + (level - a) / (b - a);
  }
  return NAN;
}

}  // namespace

TEST(Renderer, StripeEdgesLandWhereTheCameraProjects) {
  StripedPlane plane;
  // An oblique, rolled camera: the edges y = k cross the image as slanted lines.
  PinholeCamera cam = PinholeCamera::look_at({3.0, -7.0, 6.0}, {0.4, 0.3, 0.0}, {0.3, 1.0, 0.4},
                                             520, 520, 319.5, 239.5, 640, 480);
  RenderOptions options;
  options.samples_per_pixel = 16;
  const Image img = render(plane.inputs(), cam, options);
  int checked = 0;
  double worst = 0;
  for (int edge = -2; edge <= 3; ++edge) {
    for (double x = -3.0; x <= 3.0; x += 0.75) {
      const Vec3 X(x, double(edge), 0.0);
      Vec2 px;
      if (!cam.project(X, &px) || px.x() < 5 || px.x() > 634 || px.y() < 8 || px.y() > 471)
        continue;
      // Use the column through the projected point: the crossing in that
      // column is where the edge line meets it.
      const int u = int(std::lround(px.x()));
      // The edge line near X: project a second point along the edge to get its slope.
      Vec2 px2;
      ASSERT_TRUE(cam.project(X + Vec3(0.05, 0, 0), &px2));
      const double slope = (px2.y() - px.y()) / (px2.x() - px.x());
      const double expected = px.y() + slope * (u - px.x());
      const double found = crossing_row(img, u, int(expected) - 4, int(expected) + 4);
      ASSERT_TRUE(std::isfinite(found)) << "no edge near row " << expected;
      worst = std::max(worst, std::abs(found - expected));
      ++checked;
    }
  }
  EXPECT_GE(checked, 20);
  EXPECT_LT(worst, 0.5) << "largest edge offset in pixels";
}

TEST(Renderer, DepthMatchesGeometry) {
  StripedPlane plane;
  const PinholeCamera cam = PinholeCamera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 300, 300,
                                                   79.5, 59.5, 160, 120);
  std::vector<float> depth;
  render(plane.inputs(), cam, {}, &depth);
  // Looking straight down from 5 m: every pixel sees the plane at depth 5.
  for (float d : depth) ASSERT_NEAR(d, 5.0, 1e-4);
}

TEST(Renderer, BackgroundWhereNothingIsHit) {
  StripedPlane plane;
  const PinholeCamera cam = PinholeCamera::look_at({0, 0, 5}, {0, 0, 10}, {0, 1, 0}, 100, 100,
                                                   31.5, 23.5, 64, 48);
  std::vector<float> depth;
  RenderOptions options;
  const Image img = render(plane.inputs(), cam, options, &depth);
  EXPECT_EQ(img.pixel(10, 10)[0], std::uint8_t(std::lround(options.background.x() * 255)));
  EXPECT_TRUE(std::isnan(depth[0]));
}

TEST(Renderer, DeterministicAndThreadIndependent) {
  const TriangleMesh mesh = synth::make_building();
  const RayCaster caster(mesh);
  const SolidTexture texture(3);
  const RenderInputs in{&mesh, &caster, &texture, mesh.face_attribute(synth::kMaterialAttribute)};
  synth::CameraSetOptions co;
  co.count = 3;
  co.width = 160;
  co.height = 120;
  const auto cams = synth::make_cameras(mesh, co);
  const Image a = render(in, cams[1]), b = render(in, cams[1]);
  ASSERT_EQ(a.bytes(), b.bytes());
  EXPECT_TRUE(std::equal(a.data(), a.data() + a.bytes(), b.data()));
  // A different texture seed changes the picture.
  const SolidTexture other(4);
  const RenderInputs in2{&mesh, &caster, &other, mesh.face_attribute(synth::kMaterialAttribute)};
  const Image c = render(in2, cams[1]);
  EXPECT_FALSE(std::equal(a.data(), a.data() + a.bytes(), c.data()));
}

TEST(Renderer, CancelStops) {
  StripedPlane plane;
  const PinholeCamera cam = PinholeCamera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 300, 300,
                                                   79.5, 59.5, 160, 120);
  int calls = 0;
  EXPECT_THROW(render(plane.inputs(), cam, {}, nullptr,
                      [&](double, const std::string&) { return ++calls < 2; }),
               Cancelled);
  EXPECT_EQ(calls, 2);
}

TEST(RayCaster, HitsAndOcclusion) {
  const TriangleMesh box = synth::make_box(Vec3(-1, -1, -1), Vec3(1, 1, 1), 0.5, 0);
  const RayCaster caster(box);
  RayHit hit;
  ASSERT_TRUE(caster.intersect(Vec3(0.1, 0.2, 10), Vec3(0, 0, -2), &hit));
  EXPECT_NEAR(hit.distance, 9.0, 1e-5);
  EXPECT_GT(box.face_normal(hit.face).z(), 0.99);
  EXPECT_FALSE(caster.intersect(Vec3(0, 0, 10), Vec3(0, 0, 1), &hit));
  EXPECT_TRUE(caster.occluded(Vec3(0, 0, 10), Vec3(0, 0, -1), 0, 20));
  EXPECT_FALSE(caster.occluded(Vec3(0, 0, 10), Vec3(0, 0, -1), 0, 8.9));
  // A point on the surface is visible from outside: the eps rule stops the
  // segment just before it.
  EXPECT_TRUE(caster.segment_clear(Vec3(0.3, 0.3, 5), Vec3(0.3, 0.3, 1), 1e-4, 1e-6));
  EXPECT_FALSE(caster.segment_clear(Vec3(0.3, 0.3, 5), Vec3(0.3, 0.3, -1), 1e-4, 1e-6));
}

TEST(RayCaster, PacketOfFourSegmentsAgreesWithSingleSegments) {
  // A city block of boxes, segments from cameras around it to random points
  // on its surface and off it: the packet says clear exactly when all four
  // single segments are.
  TriangleMesh m = synth::make_box(Vec3(-1, -1, 0), Vec3(1, 1, 2), 0.25, 0);
  m.append(synth::make_box(Vec3(1.5, -0.5, 0), Vec3(2.5, 0.5, 3), 0.25, 0));
  const RayCaster caster(m);
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> face(0, m.num_faces() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int blocked = 0, clear = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double angle = 2 * M_PI * u(rng);
    const Vec3 eye(6 * std::cos(angle), 6 * std::sin(angle), 1 + 4 * u(rng));
    Vec3 to[4];
    bool singles = true;
    const std::size_t f = face(rng);
    for (int k = 0; k < 4; ++k) {
      const double a = u(rng), b = u(rng) * (1 - a);
      to[k] = a * m.vertices[m.faces[f][0]] + b * m.vertices[m.faces[f][1]] +
              (1 - a - b) * m.vertices[m.faces[f][2]];
      if (trial % 7 == 0 && k == 3) to[k] = eye;  // a degenerate segment: clear
      singles = singles && caster.segment_clear(eye, to[k], 1e-4, 1e-6);
    }
    const bool packet = caster.segments_clear4(eye, to, 1e-4, 1e-6);
    ASSERT_EQ(packet, singles) << "trial " << trial;
    (packet ? clear : blocked) += 1;
  }
  EXPECT_GT(clear, 200);
  EXPECT_GT(blocked, 200);
}

TEST(RayCaster, FarFromOriginKeepsPrecision) {
  // A box at UTM-like coordinates: single precision alone would be off by metres.
  const Vec3 o(500000.0, 5000000.0, 100.0);
  const TriangleMesh box = synth::make_box(o + Vec3(-1, -1, -1), o + Vec3(1, 1, 1), 0.5, 0);
  const RayCaster caster(box);
  RayHit hit;
  ASSERT_TRUE(caster.intersect(o + Vec3(0, 0, 10), Vec3(0, 0, -1), &hit));
  EXPECT_NEAR(hit.distance, 9.0, 1e-4);
}
