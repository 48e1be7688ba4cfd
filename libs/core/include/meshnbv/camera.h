// Pinhole camera of the core. The one convention (docs/conventions.md):
//   x_cam = R X + t, camera looks along +z, x right, y down;
//   pixel (u, v) = (fx x'/z' ... ) with integer coordinates at pixel CENTRES
//   (OpenCV), so the image covers [-0.5, W-0.5] x [-0.5, H-0.5];
//   an optional lens on normalised coordinates (x, y) = (X/Z, Y/Z):
//   - Brown-Conrady (OpenCV's cv::projectPoints model, k1..k6, p1, p2):
//       a = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//       x' = x a + 2 p1 x y + p2 (r^2 + 2 x^2)
//       y' = y a + p1 (r^2 + 2 y^2) + 2 p2 x y,      r^2 = x^2 + y^2
//   - equidistant fisheye (OpenCV's cv::fisheye, k1..k4):
//       theta = atan(r), theta_d = theta (1 + k1 th^2 + k2 th^4 + k3 th^6 + k4 th^8)
//       (x', y') = (theta_d / r) (x, y)
//   then u = fx x' + skew y' + cx, v = fy y' + cy.
#pragma once

#include <array>
#include <string>

#include "meshnbv/types.h"

namespace meshnbv {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length
};

// The lens model applied to normalised coordinates (docs/conventions.md).
enum class LensModel {
  Brown,    // Brown-Conrady radial k1..k3, rational k4..k6, tangential p1, p2
  Fisheye,  // equidistant fisheye, k1..k4 on the angle (k5, k6, p1, p2 must be 0)
};

// Undistortion (pixel -> ray) is iterative: converged when the re-distorted
// point is within kUndistortTolerance * (1 + |d|) of the target, in
// normalised coordinates (1e-8 px at a focal length of 10^4 px).
constexpr double kUndistortTolerance = 1e-12;

class PinholeCamera {
 public:
  double fx = 0, fy = 0, cx = 0, cy = 0;
  int width = 0, height = 0;
  LensModel lens = LensModel::Brown;
  double k1 = 0, k2 = 0, k3 = 0, k4 = 0, k5 = 0, k6 = 0;
  double p1 = 0, p2 = 0;
  double skew = 0;  // pixels: u = fx x' + skew y' + cx
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();

  // A camera at `eye` looking at `target`, with `up` (world) pointing up in
  // the image. Throws Error if up is parallel to the viewing direction.
  static PinholeCamera look_at(const Vec3& eye, const Vec3& target, const Vec3& up, double fx,
                               double fy, double cx, double cy, int width, int height);

  Mat3 K() const;
  Vec3 center() const { return -R.transpose() * t; }
  Vec3 right() const { return R.row(0).transpose(); }     // image +x in world
  Vec3 down() const { return R.row(1).transpose(); }      // image +y in world
  Vec3 forward() const { return R.row(2).transpose(); }   // viewing direction
  void set_center(const Vec3& c) { t = -R * c; }

  Vec3 world_to_camera(const Vec3& X) const { return R * X + t; }
  Vec3 camera_to_world(const Vec3& Xc) const { return R.transpose() * (Xc - t); }
  double depth(const Vec3& X) const { return R.row(2).dot(X) + t.z(); }

  // True when the projection is not K [R | t] with K = [fx 0 cx; 0 fy cy]:
  // any non-zero lens parameter, skew, or the fisheye model. False means the
  // fast linear path (pixel = K (R X + t) / z) is exact.
  bool has_distortion() const {
    return lens != LensModel::Brown || k1 != 0.0 || k2 != 0.0 || k3 != 0.0 || k4 != 0.0 ||
           k5 != 0.0 || k6 != 0.0 || p1 != 0.0 || p2 != 0.0 || skew != 0.0;
  }
  // Whether the lens (not counting skew) bends rays.
  bool has_lens_distortion() const;
  // Clears every lens parameter and skew: a pinhole camera.
  void clear_lens();
  // One line naming the lens and its non-zero parameters ("pinhole", "brown k1=..").
  std::string lens_description() const;
  Vec2 distort(const Vec2& normalized) const;
  // Inverse of distort() by damped Newton iterations (kUndistortTolerance).
  // try_undistort returns false where it does not converge (or, fisheye,
  // where the ray is 90 degrees or more off axis); undistort throws Error.
  bool try_undistort(const Vec2& distorted, Vec2* normalized) const;
  Vec2 undistort(const Vec2& distorted) const;
  // Pixel <-> distorted normalised coordinates (fx, fy, cx, cy, skew).
  Vec2 to_pixel(const Vec2& distorted) const;
  Vec2 from_pixel(const Vec2& pixel) const;

  // Projects X. Returns false (pixel untouched) when X is not in front of the
  // camera (depth <= 0). The pixel may lie outside the image: see in_image().
  bool project(const Vec3& X, Vec2* pixel, double* depth_out = nullptr) const;
  // The world point at z-depth `depth` seen at `pixel`.
  Vec3 backproject(const Vec2& pixel, double depth) const;
  // Ray from the centre through `pixel`.
  Ray viewing_ray(const Vec2& pixel) const;
  // SPEC section 2: inside [0, W-1] x [0, H-1].
  bool in_image(const Vec2& pixel) const;
  // World positions of the image's outer corners (-0.5,-0.5), (W-0.5,-0.5),
  // (W-0.5,H-0.5), (-0.5,H-0.5) at z-depth `depth`.
  std::array<Vec3, 4> frustum_corners(double depth) const;

  // Throws Error (prefixed with `what`) for non-finite values, fx/fy <= 0,
  // size <= 0, a principal point far outside the image, R not a rotation,
  // fisheye with k5, k6, p1 or p2 set, or a lens that does not invert over
  // the image (undistortion fails or the mapping folds over on a 9x9 grid
  // of the image including its corners).
  void check(const std::string& what = "camera") const;
  // The lens part of check().
  void check_lens(const std::string& what = "camera") const;
};

}  // namespace meshnbv
