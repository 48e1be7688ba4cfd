// Lens models of PinholeCamera against OpenCV, an independent implementation
// of the same conventions (docs/conventions.md):
// - Brown-Conrady = cv::projectPoints with distCoeffs (k1, k2, p1, p2, k3, k4, k5, k6);
// - equidistant fisheye = cv::fisheye::projectPoints with D = (k1, k2, k3, k4)
//   and alpha = skew / fx (OpenCV: u = fx (x' + alpha y') + cx).
// Pixel centres at integers in both. Undistortion: its stated tolerance
// (kUndistortTolerance) and its error where it cannot converge.
#include <cmath>
#include <random>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "meshnbv/camera.h"
#include "meshnbv/error.h"
#include "test_util.h"

using namespace meshnbv;

namespace {

PinholeCamera base_camera() {
  // 1200x800, looking from (1, 2, 10) at the origin, fx != fy, off-centre.
  return PinholeCamera::look_at({1, 2, 10}, {0, 0, 0}, {0, 1, 0}, 900, 880, 610.3, 390.8, 1200,
                                800);
}

// Random points in front of the camera whose rays are within ~35 degrees of the axis.
std::vector<Vec3> points_in_view(const PinholeCamera& cam, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lateral(-0.6, 0.6), depth(2.0, 20.0);
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    const double z = depth(rng);
    points.push_back(cam.camera_to_world(Vec3(lateral(rng) * z, lateral(rng) * z, z)));
  }
  return points;
}

cv::Mat rodrigues(const Mat3& R) {
  cv::Mat Rm(3, 3, CV_64F), rvec;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Rm.at<double>(r, c) = R(r, c);
  cv::Rodrigues(Rm, rvec);
  return rvec;
}

std::vector<cv::Point3d> to_cv(const std::vector<Vec3>& points) {
  std::vector<cv::Point3d> out;
  for (const Vec3& p : points) out.emplace_back(p.x(), p.y(), p.z());
  return out;
}

void expect_same_pixels(const PinholeCamera& cam, const std::vector<Vec3>& points,
                        const std::vector<cv::Point2d>& expected, double tol) {
  ASSERT_EQ(points.size(), expected.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    Vec2 px;
    ASSERT_TRUE(cam.project(points[i], &px));
    EXPECT_NEAR(px.x(), expected[i].x, tol) << i;
    EXPECT_NEAR(px.y(), expected[i].y, tol) << i;
  }
}

std::vector<cv::Point2d> opencv_brown(const PinholeCamera& c, const std::vector<Vec3>& points) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const cv::Mat D = (cv::Mat_<double>(1, 8) << c.k1, c.k2, c.p1, c.p2, c.k3, c.k4, c.k5, c.k6);
  const cv::Mat tvec = (cv::Mat_<double>(3, 1) << c.t.x(), c.t.y(), c.t.z());
  std::vector<cv::Point2d> out;
  cv::projectPoints(to_cv(points), rodrigues(c.R), tvec, K, D, out);
  return out;
}

std::vector<cv::Point2d> opencv_fisheye(const PinholeCamera& c, const std::vector<Vec3>& points) {
  const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const cv::Vec4d D(c.k1, c.k2, c.k3, c.k4);
  const cv::Mat rvec = rodrigues(c.R);
  const cv::Vec3d tvec(c.t.x(), c.t.y(), c.t.z());
  std::vector<cv::Point2d> out;
  cv::fisheye::projectPoints(to_cv(points), out, rvec, tvec, K, D, c.skew / c.fx);
  return out;
}

void expect_backprojection_inverts(const PinholeCamera& cam) {
  for (double u : {-0.5, 0.0, 300.25, 610.0, 1199.5})
    for (double v : {-0.5, 0.0, 123.75, 799.5}) {
      const Vec2 pixel(u, v);
      const Vec3 X = cam.backproject(pixel, 5.0);
      Vec2 back;
      double depth = 0;
      ASSERT_TRUE(cam.project(X, &back, &depth));
      EXPECT_NEAR(depth, 5.0, 1e-9);
      // kUndistortTolerance (1e-12 normalised) is ~1e-9 px at f = 900.
      EXPECT_NEAR((back - pixel).norm(), 0, 1e-8) << pixel.transpose();
    }
}

}  // namespace

TEST(Lens, PinholeHasNoDistortion) {
  PinholeCamera cam = base_camera();
  EXPECT_FALSE(cam.has_distortion());
  EXPECT_EQ(cam.lens_description(), "pinhole");
  // Any single lens parameter, skew or the fisheye model leaves the linear path.
  double PinholeCamera::*params[] = {&PinholeCamera::k1, &PinholeCamera::k2, &PinholeCamera::k3,
                                     &PinholeCamera::k4, &PinholeCamera::k5, &PinholeCamera::k6,
                                     &PinholeCamera::p1, &PinholeCamera::p2, &PinholeCamera::skew};
  for (auto p : params) {
    PinholeCamera c = cam;
    c.*p = 1e-9;
    EXPECT_TRUE(c.has_distortion());
  }
  PinholeCamera fish = cam;
  fish.lens = LensModel::Fisheye;
  EXPECT_TRUE(fish.has_distortion());
  PinholeCamera cleared = fish;
  cleared.k3 = 0.2;
  cleared.clear_lens();
  EXPECT_FALSE(cleared.has_distortion());
}

TEST(Lens, RadialTangentialMatchesOpenCvProjectPoints) {
  PinholeCamera cam = base_camera();
  cam.k1 = -0.21;
  cam.k2 = 0.07;
  cam.k3 = -0.012;
  cam.p1 = 0.0013;
  cam.p2 = -0.0021;
  ASSERT_NO_THROW(cam.check());
  const auto points = points_in_view(cam, 200, 1);
  expect_same_pixels(cam, points, opencv_brown(cam, points), 1e-9);
  expect_backprojection_inverts(cam);
}

TEST(Lens, RationalModelMatchesOpenCvProjectPoints) {
  PinholeCamera cam = base_camera();
  cam.k1 = 0.4;
  cam.k2 = -0.1;
  cam.k3 = 0.02;
  cam.k4 = 0.55;
  cam.k5 = -0.05;
  cam.k6 = 0.01;
  cam.p1 = -0.001;
  cam.p2 = 0.0007;
  ASSERT_NO_THROW(cam.check());
  const auto points = points_in_view(cam, 200, 2);
  expect_same_pixels(cam, points, opencv_brown(cam, points), 1e-9);
  expect_backprojection_inverts(cam);
}

TEST(Lens, FisheyeMatchesOpenCvFisheyeProjectPoints) {
  PinholeCamera cam = base_camera();
  cam.lens = LensModel::Fisheye;
  cam.fx = cam.fy = 600;  // a wide lens: 1200 px wide at f = 600 is ~90 degrees
  cam.k1 = 0.031;
  cam.k2 = -0.012;
  cam.k3 = 0.0042;
  cam.k4 = -0.0009;
  cam.skew = 0.8;
  ASSERT_NO_THROW(cam.check());
  auto points = points_in_view(cam, 200, 3);
  for (const Vec3& far_off_axis : {Vec3(3, 0.5, 1), Vec3(-2, -2, 0.5)})
    points.push_back(cam.camera_to_world(far_off_axis));  // 70 and 80 degrees off axis
  expect_same_pixels(cam, points, opencv_fisheye(cam, points), 1e-9);
  expect_backprojection_inverts(cam);
}

TEST(Lens, SkewIsInKAndThePixelMapping) {
  // u = fx x' + skew y' + cx, v = fy y' + cy, written out.
  PinholeCamera cam = base_camera();
  cam.skew = 2.5;
  cam.k1 = -0.05;
  const Vec3 X = cam.camera_to_world(Vec3(0.3, -0.2, 2.0));
  const double x = 0.15, y = -0.1, a = 1 + cam.k1 * (x * x + y * y);
  Vec2 px;
  ASSERT_TRUE(cam.project(X, &px));
  EXPECT_NEAR(px.x(), cam.fx * x * a + cam.skew * y * a + cam.cx, 1e-9);
  EXPECT_NEAR(px.y(), cam.fy * y * a + cam.cy, 1e-9);
  PinholeCamera linear = cam;
  linear.k1 = 0;
  const Vec3 h = linear.K() * linear.world_to_camera(X);
  ASSERT_TRUE(linear.project(X, &px));
  EXPECT_NEAR(px.x(), h.x() / h.z(), 1e-9);
  EXPECT_NEAR(px.y(), h.y() / h.z(), 1e-9);
  expect_backprojection_inverts(cam);
}

TEST(Lens, UndistortMeetsItsStatedTolerance) {
  PinholeCamera cam = base_camera();
  cam.k1 = -0.3;
  cam.k2 = 0.1;
  cam.p1 = 0.002;
  for (const Vec2& d : {Vec2(0, 0), Vec2(0.5, -0.4), Vec2(-0.66, 0.44), Vec2(1e-9, 0)}) {
    const Vec2 n = cam.undistort(d);
    EXPECT_LE((cam.distort(n) - d).norm(), kUndistortTolerance * (1 + d.norm())) << d.transpose();
  }
}

TEST(Lens, UndistortThrowsWhereItCannotConverge) {
  // 1 + k1 r^2 with k1 < 0 turns over at r = 1/sqrt(3 |k1|): distorted radii
  // beyond its maximum (2/3 / sqrt(3 |k1|)) have no preimage.
  PinholeCamera cam = base_camera();
  cam.k1 = -0.5;
  const double r_max = 2.0 / 3.0 / std::sqrt(1.5);
  Vec2 n;
  EXPECT_TRUE(cam.try_undistort(Vec2(0.9 * r_max, 0), &n));
  EXPECT_FALSE(cam.try_undistort(Vec2(1.1 * r_max, 0), &n));
  MESHNBV_EXPECT_ERROR_CONTAINS(cam.undistort(Vec2(1.1 * r_max, 0)), "did not converge");
  // Fisheye: rays at 90 degrees or more are not in front of the camera.
  PinholeCamera fish = base_camera();
  fish.lens = LensModel::Fisheye;
  EXPECT_FALSE(fish.try_undistort(Vec2(1.6, 0), &n));  // theta_d = theta = 1.6 > pi/2
  EXPECT_TRUE(fish.try_undistort(Vec2(1.5, 0), &n));
  EXPECT_NEAR(n.x(), std::tan(1.5), 1e-9);
}

TEST(Lens, CheckRejectsLensThatDoesNotInvertOverTheImage) {
  PinholeCamera cam = base_camera();
  cam.k1 = -0.5;  // turns over at r ~ 0.54 < the corners' ~0.85
  MESHNBV_EXPECT_ERROR_CONTAINS(cam.check("view 'a'"), "does not invert at pixel");
  cam.k1 = -0.05;
  EXPECT_NO_THROW(cam.check());
  PinholeCamera fish = base_camera();
  fish.lens = LensModel::Fisheye;
  fish.p1 = 0.01;
  MESHNBV_EXPECT_ERROR_CONTAINS(fish.check(), "fisheye model takes k1..k4 only");
  PinholeCamera nan = base_camera();
  nan.k5 = NAN;
  MESHNBV_EXPECT_ERROR_CONTAINS(nan.check(), "non-finite");
}

TEST(Lens, DescriptionNamesModelAndParameters) {
  PinholeCamera cam = base_camera();
  cam.k1 = -0.1;
  cam.p2 = 0.002;
  EXPECT_EQ(cam.lens_description(), "brown k1=-0.1 p2=0.002");
  cam.clear_lens();
  cam.lens = LensModel::Fisheye;
  cam.k4 = 0.01;
  EXPECT_EQ(cam.lens_description(), "fisheye k4=0.01");
}
