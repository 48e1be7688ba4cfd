// Visibility (SPEC section 2) at the edges of its rules, on geometry whose
// answer is known exactly: the occlusion epsilon, the image border, the
// camera plane, and PRI's grazing-angle limit. Camera for most tests: at
// the origin looking along +z, image x along +x and y along +y (R = I,
// t = 0), so that a point (x, y, z) projects to (fx x/z + cx, fy y/z + cy)
// with no rounding for the values chosen.
#include <cmath>
#include <vector>

#include "meshnbv/pri.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/visibility.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

// 64 x 48 pixels, f = 64: at depth 2, x = 2 (u - 31.5) / 64 exactly.
PinholeCamera small_axis_camera() { return test::centred_camera(64, 64, 48); }

// The point at depth z that projects to pixel (u, v) of small_axis_camera().
Vec3 at_pixel(double u, double v, double z) {
  return Vec3((u - 31.5) / 64 * z, (v - 23.5) / 64 * z, z);
}

// A square [-s, s]^2 in the plane z = depth (two faces), facing -z.
TriangleMesh square_at(double depth, double s) {
  TriangleMesh m;
  m.vertices = {Vec3(-s, -s, depth), Vec3(s, -s, depth), Vec3(s, s, depth), Vec3(-s, s, depth)};
  m.faces = {{0, 2, 1}, {0, 3, 2}};
  return m;
}

}  // namespace

// --- the occlusion epsilon: the segment stops at (1 - eps) L - bias ------------

TEST(VisibilityEpsilon, OccluderJustInsideTheRelativeEpsilonHides) {
  // Point at L = 10 on the axis; eps = 1e-4, no bias: the segment is
  // tested up to 9.999. An occluder 1e-5 L before that hides the point.
  const double L = 10, eps = 1e-4, t_max = (1 - eps) * L;
  const TriangleMesh occluder = square_at(t_max - 1e-5 * L, 1.0);
  const RayCaster caster(occluder);
  EXPECT_FALSE(point_visible(caster, small_axis_camera(), Vec3(0, 0, L), eps, 0.0));
}

TEST(VisibilityEpsilon, OccluderJustOutsideTheRelativeEpsilonDoesNotHide) {
  // 1e-5 L past the end of the tested segment (inside the band of width
  // eps L before the point, where the point's own faces lie): visible.
  const double L = 10, eps = 1e-4, t_max = (1 - eps) * L;
  const TriangleMesh occluder = square_at(t_max + 1e-5 * L, 1.0);
  const RayCaster caster(occluder);
  EXPECT_TRUE(point_visible(caster, small_axis_camera(), Vec3(0, 0, L), eps, 0.0));
}

TEST(VisibilityEpsilon, AbsoluteBiasShortensTheSegmentToo) {
  // eps = 0, bias 0.01: the segment ends at L - 0.01.
  const double L = 10, bias = 0.01;
  {
    const TriangleMesh m = square_at(L - bias - 1e-4, 1.0);
    const RayCaster caster(m);
    EXPECT_FALSE(point_visible(caster, small_axis_camera(), Vec3(0, 0, L), 0.0, bias));
  }
  {
    const TriangleMesh m = square_at(L - bias + 1e-4, 1.0);
    const RayCaster caster(m);
    EXPECT_TRUE(point_visible(caster, small_axis_camera(), Vec3(0, 0, L), 0.0, bias));
  }
  // Both together: (1 - eps) L - bias.
  const double eps = 1e-3, end = (1 - eps) * L - bias;  // 9.98
  {
    const TriangleMesh m = square_at(end - 1e-4, 1.0);
    const RayCaster caster(m);
    EXPECT_FALSE(point_visible(caster, small_axis_camera(), Vec3(0, 0, L), eps, bias));
  }
  {
    const TriangleMesh m = square_at(end + 1e-4, 1.0);
    const RayCaster caster(m);
    EXPECT_TRUE(point_visible(caster, small_axis_camera(), Vec3(0, 0, L), eps, bias));
  }
}

TEST(VisibilityEpsilon, VertexVisibilityWithTheSpecDefaults) {
  // A mesh with the vertex of interest on a far square (its own faces at
  // distance L exactly) and an occluding plate either 2 eps L or eps L / 2
  // before it (SPEC: eps = 1e-4, bias 1e-6 of the bounding-box diagonal,
  // here 2e-5 m, well under eps L = 1e-3 m).
  const double L = 10;
  for (const auto& [gap, visible] : {std::pair{2e-4 * L, false}, std::pair{0.5e-4 * L, true}}) {
    TriangleMesh m = square_at(L, 1.0);
    // A small plate over the far square's vertex 0 = (-1, -1, L), on the
    // line from the camera: the plate z = L - gap, around (-1, -1) (L - gap) / L.
    const double z = L - gap, k = z / L;
    TriangleMesh plate;
    plate.vertices = {Vec3(-k - 0.05, -k - 0.05, z), Vec3(-k + 0.05, -k - 0.05, z),
                      Vec3(-k + 0.05, -k + 0.05, z), Vec3(-k - 0.05, -k + 0.05, z)};
    plate.faces = {{0, 2, 1}, {0, 3, 2}};
    m.append(plate);
    const RayCaster caster(m);
    PinholeCamera wide = small_axis_camera();
    wide.fx = wide.fy = 8;  // the whole far square in the image
    const VertexVisibility vis(m, caster, {wide});
    EXPECT_EQ(vis.visible(0, 0), visible) << "gap " << gap;
    EXPECT_TRUE(vis.visible(2, 0));  // the opposite corner: nothing in front
  }
}

// --- the image border: inside [0, W-1] x [0, H-1] --------------------------------

namespace {
// Nothing to occlude: a small square behind the camera.
struct Empty {
  TriangleMesh mesh = square_at(-100, 0.1);
  RayCaster caster{mesh};
};
}  // namespace

TEST(VisibilityBorder, VertexExactlyOnTheImageBorderIsVisible) {
  const Empty e;
  const PinholeCamera cam = small_axis_camera();
  for (const Vec2& px : {Vec2(0, 20), Vec2(63, 20), Vec2(10, 0), Vec2(10, 47), Vec2(0, 0),
                         Vec2(63, 47), Vec2(0, 47), Vec2(63, 0)}) {
    const Vec3 p = at_pixel(px.x(), px.y(), 2.0);
    Vec2 projected;
    ASSERT_TRUE(cam.project(p, &projected));
    ASSERT_EQ(projected, px);  // exactly on the border, no rounding
    EXPECT_TRUE(point_visible(e.caster, cam, p, 1e-4, 0.0)) << px.transpose();
  }
}

TEST(VisibilityBorder, VertexJustBeyondTheBorderIsNot) {
  // 1/64 px beyond; also within the image's pixel extent [-0.5, W - 0.5]:
  // the SPEC's rule is on pixel centres.
  const Empty e;
  const PinholeCamera cam = small_axis_camera();
  for (const Vec2& px : {Vec2(-1.0 / 64, 20), Vec2(63 + 1.0 / 64, 20), Vec2(10, -1.0 / 64),
                         Vec2(10, 47 + 1.0 / 64), Vec2(-0.25, 20), Vec2(63.25, 47)}) {
    const Vec3 p = at_pixel(px.x(), px.y(), 2.0);
    Vec2 projected;
    ASSERT_TRUE(cam.project(p, &projected));
    ASSERT_EQ(projected, px);
    EXPECT_FALSE(point_visible(e.caster, cam, p, 1e-4, 0.0)) << px.transpose();
  }
}

// --- behind the camera: z_cam > 0 -----------------------------------------------

TEST(VisibilityBehind, PointBehindTheCameraIsNotVisible) {
  // Its central projection would land on the image centre.
  const Empty e;
  const PinholeCamera cam = small_axis_camera();
  EXPECT_FALSE(point_visible(e.caster, cam, Vec3(0, 0, -1), 1e-4, 0.0));
  EXPECT_FALSE(point_visible(e.caster, cam, at_pixel(10, 10, -2.0), 1e-4, 0.0));
  Vec2 px;
  EXPECT_FALSE(cam.project(Vec3(0, 0, -1), &px));
}

TEST(VisibilityBehind, PointInTheCameraPlaneIsNotVisible) {
  const Empty e;
  const PinholeCamera cam = small_axis_camera();
  EXPECT_FALSE(point_visible(e.caster, cam, Vec3(0.5, 0.2, 0.0), 1e-4, 0.0));
  EXPECT_FALSE(point_visible(e.caster, cam, Vec3(0, 0, 0), 1e-4, 0.0));
  // Just in front, on the axis: visible.
  EXPECT_TRUE(point_visible(e.caster, cam, Vec3(0, 0, 1e-9), 1e-4, 0.0));
}

TEST(VisibilityBehind, CameraTurnedAwaySeesNothingOfTheMesh) {
  // The far square of VertexVisibilityWithTheSpecDefaults, from a camera
  // looking along -z: every vertex behind it.
  const TriangleMesh m = square_at(10, 1.0);
  const RayCaster caster(m);
  PinholeCamera away = small_axis_camera();
  away.fx = away.fy = 8;
  away.R = Eigen::AngleAxisd(M_PI, Vec3::UnitY()).toRotationMatrix();  // forward = -z
  ASSERT_NEAR(away.forward().z(), -1.0, 1e-15);
  const VertexVisibility vis(m, caster, {away});
  for (std::size_t v = 0; v < m.num_vertices(); ++v) EXPECT_FALSE(vis.visible(v, 0)) << v;
}

// --- PRI's grazing-angle limit: a view counts when the angle <= max -----------

namespace {

// One triangle whose normal is exactly (0.96, 0, -0.28) (a 7-24-25
// triangle: cross product (144, 0, -42), length 150) and whose centroid is
// exactly (0, 0, 40), seen by two identical cameras at the origin looking
// along +z: the cosine of the viewing angle is exactly 0.28 (73.74 degrees).
Scene grazing_scene() {
  Scene s;
  s.mesh.vertices = {Vec3(-7, -1, 16), Vec3(7, -1, 64), Vec3(0, 2, 40)};
  s.mesh.faces = {{0, 2, 1}};
  PinholeCamera cam = small_axis_camera();
  cam.fx = cam.fy = 100;
  cam.cx = 99.5;
  cam.cy = 74.5;
  cam.width = 200;
  cam.height = 150;
  for (int i = 0; i < 2; ++i) {
    View v;
    v.label = "v" + std::to_string(i);
    v.camera = cam;
    v.image_path = "unused.png";  // view selection reads no image
    s.views.push_back(v);
  }
  return s;
}

}  // namespace

TEST(VisibilityGrazing, AngleExactlyAtMaxIncidenceAngleCounts) {
  const Scene s = grazing_scene();
  const Vec3 n = s.mesh.face_normal(0), centroid = s.mesh.face_centroid(0);
  ASSERT_EQ(n, Vec3(0.96, 0, -0.28));
  ASSERT_EQ(centroid, Vec3(0, 0, 40));
  const double cosine = n.dot((s.views[0].camera.center() - centroid).normalized());
  ASSERT_EQ(cosine, 0.28);
  // A max angle (degrees) whose cosine, as the option is converted, is
  // exactly 0.28: found by stepping from acos(0.28) one ulp at a time.
  const double a0 = std::acos(0.28) * 180 / M_PI;
  double exact = std::nan("");
  for (int i = 0; i < 4096 && std::isnan(exact); ++i) {
    double up = a0, down = a0;
    for (int j = 0; j < i; ++j) up = std::nextafter(up, 90.0), down = std::nextafter(down, 0.0);
    if (std::cos(up * M_PI / 180.0) == 0.28) exact = up;
    else if (std::cos(down * M_PI / 180.0) == 0.28) exact = down;
  }
  ASSERT_FALSE(std::isnan(exact)) << "no double angle has cos == 0.28 on this platform";
  PriOptions o;
  o.max_incidence_angle = exact;
  EXPECT_EQ(select_pri_views(s, o).faces[0].views, (std::vector<int>{0, 1}));
}

TEST(VisibilityGrazing, AngleJustOverMaxIncidenceAngleDoesNotCount) {
  const Scene s = grazing_scene();
  const double angle = std::acos(0.28) * 180 / M_PI;  // 73.7398 degrees
  PriOptions o;
  o.max_incidence_angle = angle - 1e-9;
  EXPECT_TRUE(select_pri_views(s, o).faces[0].views.empty());
  o.max_incidence_angle = angle + 1e-9;
  EXPECT_EQ(select_pri_views(s, o).faces[0].views, (std::vector<int>{0, 1}));
  o.max_incidence_angle = 90;  // the SPEC's plain back-face rule
  EXPECT_EQ(select_pri_views(s, o).faces[0].views, (std::vector<int>{0, 1}));
}

TEST(VisibilityGrazing, BackFacingFaceIsNotVisibleAtAnyMaxAngle) {
  Scene s = grazing_scene();
  std::swap(s.mesh.faces[0][1], s.mesh.faces[0][2]);  // normal (-0.96, 0, 0.28): away
  PriOptions o;
  o.max_incidence_angle = 90;
  EXPECT_TRUE(select_pri_views(s, o).faces[0].views.empty());
}
