// Pinhole camera of the core. The one convention (docs/conventions.md):
//   x_cam = R X + t, camera looks along +z, x right, y down;
//   pixel (u, v) = (fx x'/z' ... ) with integer coordinates at pixel CENTRES
//   (OpenCV), so the image covers [-0.5, W-0.5] x [-0.5, H-0.5];
//   optional radial distortion on normalised coordinates:
//   (x, y) -> (x, y) * (1 + k1 r^2 + k2 r^4), r^2 = x^2 + y^2.
#pragma once

#include <array>
#include <string>

#include "meshnbv/types.h"

namespace meshnbv {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length
};

class PinholeCamera {
 public:
  double fx = 0, fy = 0, cx = 0, cy = 0;
  int width = 0, height = 0;
  double k1 = 0, k2 = 0;
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

  bool has_distortion() const { return k1 != 0.0 || k2 != 0.0; }
  Vec2 distort(const Vec2& normalized) const;
  // Inverse of distort() by Newton iterations; exact for k1 = k2 = 0.
  Vec2 undistort(const Vec2& distorted) const;

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
  // size <= 0, a principal point far outside the image, or R not a rotation.
  void check(const std::string& what = "camera") const;
};

}  // namespace meshnbv
