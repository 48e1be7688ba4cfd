// PinholeCamera: x_cam = R X + t, +z forward, y down, pixel centres at integers.
#include <cmath>

#include "meshnbv/camera.h"
#include "meshnbv/error.h"
#include "test_util.h"

using namespace meshnbv;

namespace {
PinholeCamera test_camera() {
  // 640x480, looking from (1, 2, 10) at (0.5, -0.3, 0) with world +y up.
  return PinholeCamera::look_at({1, 2, 10}, {0.5, -0.3, 0}, {0, 1, 0}, 800, 780, 319.5, 239.5,
                                640, 480);
}
}  // namespace

TEST(Camera, LookAtPutsTargetAtPrincipalPoint) {
  const PinholeCamera cam = test_camera();
  Vec2 px;
  double depth = 0;
  ASSERT_TRUE(cam.project({0.5, -0.3, 0}, &px, &depth));
  EXPECT_NEAR(px.x(), 319.5, 1e-9);
  EXPECT_NEAR(px.y(), 239.5, 1e-9);
  EXPECT_NEAR(depth, (Vec3(1, 2, 10) - Vec3(0.5, -0.3, 0)).norm(), 1e-9);
  EXPECT_NEAR((cam.center() - Vec3(1, 2, 10)).norm(), 0, 1e-12);
  EXPECT_NEAR(cam.R.determinant(), 1.0, 1e-12);
}

TEST(Camera, WorldUpIsImageUp) {
  // Camera on +z looking at the origin, +y up: a point above the target
  // projects above the centre (smaller v), a point to +x to the right.
  const auto cam = PinholeCamera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 500, 500, 100, 100,
                                          201, 201);
  Vec2 up, right;
  ASSERT_TRUE(cam.project({0, 1, 0}, &up));
  ASSERT_TRUE(cam.project({1, 0, 0}, &right));
  EXPECT_NEAR(up.x(), 100, 1e-9);
  EXPECT_NEAR(up.y(), 100 - 500 * 1.0 / 5.0, 1e-9);
  EXPECT_NEAR(right.x(), 100 + 500 * 1.0 / 5.0, 1e-9);
  EXPECT_NEAR(right.y(), 100, 1e-9);
}

TEST(Camera, ProjectMatchesKRt) {
  const PinholeCamera cam = test_camera();
  const Vec3 X(0.2, 0.4, -1.0);
  const Vec3 h = cam.K() * (cam.R * X + cam.t);
  Vec2 px;
  ASSERT_TRUE(cam.project(X, &px));
  EXPECT_NEAR(px.x(), h.x() / h.z(), 1e-9);
  EXPECT_NEAR(px.y(), h.y() / h.z(), 1e-9);
}

TEST(Camera, BehindCameraDoesNotProject) {
  const PinholeCamera cam = test_camera();
  Vec2 px(-7, -7);
  EXPECT_FALSE(cam.project(cam.center() - 3.0 * cam.forward(), &px));
  EXPECT_EQ(px, Vec2(-7, -7));
}

TEST(Camera, BackprojectInvertsProjectWithDistortion) {
  PinholeCamera cam = test_camera();
  cam.k1 = -0.12;
  cam.k2 = 0.03;
  for (const Vec2& pixel : {Vec2(0, 0), Vec2(639, 479), Vec2(100.25, 400.75), Vec2(319.5, 239.5)}) {
    const Vec3 X = cam.backproject(pixel, 7.5);
    Vec2 back;
    double depth;
    ASSERT_TRUE(cam.project(X, &back, &depth));
    EXPECT_NEAR(depth, 7.5, 1e-9);
    EXPECT_NEAR((back - pixel).norm(), 0, 1e-8) << pixel.transpose();
  }
}

TEST(Camera, DistortionIsRadialPolynomial) {
  PinholeCamera cam = test_camera();
  cam.k1 = 0.1;
  cam.k2 = -0.05;
  const Vec2 n(0.3, -0.2);
  const double r2 = n.squaredNorm();
  EXPECT_NEAR((cam.distort(n) - n * (1 + 0.1 * r2 - 0.05 * r2 * r2)).norm(), 0, 1e-15);
  EXPECT_NEAR((cam.undistort(cam.distort(n)) - n).norm(), 0, 1e-12);
}

TEST(Camera, ViewingRayPassesThroughPixel) {
  const PinholeCamera cam = test_camera();
  const Ray ray = cam.viewing_ray({10, 470});
  EXPECT_NEAR(ray.direction.norm(), 1.0, 1e-12);
  Vec2 px;
  ASSERT_TRUE(cam.project(ray.origin + 4.0 * ray.direction, &px));
  EXPECT_NEAR(px.x(), 10, 1e-9);
  EXPECT_NEAR(px.y(), 470, 1e-9);
}

TEST(Camera, FrustumCornersAreImageCorners) {
  const PinholeCamera cam = test_camera();
  const auto corners = cam.frustum_corners(3.0);
  const Vec2 expected[4] = {{-0.5, -0.5}, {639.5, -0.5}, {639.5, 479.5}, {-0.5, 479.5}};
  for (int i = 0; i < 4; ++i) {
    Vec2 px;
    double depth;
    ASSERT_TRUE(cam.project(corners[i], &px, &depth));
    EXPECT_NEAR((px - expected[i]).norm(), 0, 1e-9);
    EXPECT_NEAR(depth, 3.0, 1e-12);
  }
}

TEST(Camera, InImageIsClosedPixelCentreRange) {
  const PinholeCamera cam = test_camera();
  EXPECT_TRUE(cam.in_image({0, 0}));
  EXPECT_TRUE(cam.in_image({639, 479}));
  EXPECT_FALSE(cam.in_image({639.01, 10}));
  EXPECT_FALSE(cam.in_image({-0.01, 10}));
  EXPECT_FALSE(cam.in_image({NAN, 10}));
}

TEST(Camera, CheckRejectsBadIntrinsics) {
  PinholeCamera cam = test_camera();
  EXPECT_NO_THROW(cam.check());
  PinholeCamera zero = cam;
  zero.fx = 0;
  MESHNBV_EXPECT_ERROR_CONTAINS(zero.check("view 'a'"), "focal length must be positive");
  PinholeCamera nan = cam;
  nan.t.x() = NAN;
  MESHNBV_EXPECT_ERROR_CONTAINS(nan.check(), "non-finite");
  PinholeCamera size = cam;
  size.width = 0;
  MESHNBV_EXPECT_ERROR_CONTAINS(size.check(), "image size");
  PinholeCamera skew = cam;
  skew.R(0, 1) += 0.1;
  MESHNBV_EXPECT_ERROR_CONTAINS(skew.check(), "not a rotation");
  PinholeCamera mirror = cam;
  mirror.R.row(0) *= -1;
  MESHNBV_EXPECT_ERROR_CONTAINS(mirror.check(), "not a rotation");
  PinholeCamera far = cam;
  far.cx = 5000;
  MESHNBV_EXPECT_ERROR_CONTAINS(far.check(), "principal point");
}

TEST(Camera, LookAtRejectsParallelUp) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      PinholeCamera::look_at({0, 0, 5}, {0, 0, 0}, {0, 0, 1}, 1, 1, 0, 0, 2, 2), "parallel");
}
