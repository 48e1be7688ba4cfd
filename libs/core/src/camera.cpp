#include "meshnbv/camera.h"

#include <cmath>
#include <sstream>

#include <Eigen/LU>

#include "meshnbv/error.h"

namespace meshnbv {

PinholeCamera PinholeCamera::look_at(const Vec3& eye, const Vec3& target, const Vec3& up,
                                     double fx, double fy, double cx, double cy, int width,
                                     int height) {
  Vec3 z = target - eye;
  if (!(z.norm() > 0)) throw Error("look_at: eye and target coincide");
  z.normalize();
  Vec3 x = z.cross(up);  // image x = (image y = down) x (forward), down = -up
  if (!(x.norm() > 1e-12 * up.norm()) || !(up.norm() > 0))
    throw Error("look_at: the up vector is parallel to the viewing direction");
  x.normalize();
  Vec3 y = z.cross(x);
  PinholeCamera cam;
  cam.R.row(0) = x.transpose();
  cam.R.row(1) = y.transpose();
  cam.R.row(2) = z.transpose();
  cam.set_center(eye);
  cam.fx = fx;
  cam.fy = fy;
  cam.cx = cx;
  cam.cy = cy;
  cam.width = width;
  cam.height = height;
  return cam;
}

Mat3 PinholeCamera::K() const {
  Mat3 k;
  k << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  return k;
}

Vec2 PinholeCamera::distort(const Vec2& n) const {
  if (!has_distortion()) return n;
  const double r2 = n.squaredNorm();
  return n * (1.0 + k1 * r2 + k2 * r2 * r2);
}

Vec2 PinholeCamera::undistort(const Vec2& d) const {
  if (!has_distortion()) return d;
  // Solve distort(n) = d by Newton on the radius: f(r) = r (1 + k1 r^2 + k2 r^4) - rd.
  const double rd = d.norm();
  if (rd == 0) return d;
  double r = rd;
  for (int i = 0; i < 20; ++i) {
    const double r2 = r * r;
    const double f = r * (1 + k1 * r2 + k2 * r2 * r2) - rd;
    const double df = 1 + 3 * k1 * r2 + 5 * k2 * r2 * r2;
    if (df <= 0) break;  // past the turning point of the polynomial
    const double step = f / df;
    r -= step;
    if (std::abs(step) < 1e-15 * (1 + r)) break;
  }
  return d * (r / rd);
}

bool PinholeCamera::project(const Vec3& X, Vec2* pixel, double* depth_out) const {
  const Vec3 xc = world_to_camera(X);
  if (!(xc.z() > 0)) return false;
  const Vec2 n = distort(Vec2(xc.x() / xc.z(), xc.y() / xc.z()));
  *pixel = Vec2(fx * n.x() + cx, fy * n.y() + cy);
  if (depth_out) *depth_out = xc.z();
  return true;
}

Vec3 PinholeCamera::backproject(const Vec2& pixel, double depth) const {
  const Vec2 n = undistort(Vec2((pixel.x() - cx) / fx, (pixel.y() - cy) / fy));
  return camera_to_world(Vec3(n.x() * depth, n.y() * depth, depth));
}

Ray PinholeCamera::viewing_ray(const Vec2& pixel) const {
  const Vec3 c = center();
  return {c, (backproject(pixel, 1.0) - c).normalized()};
}

bool PinholeCamera::in_image(const Vec2& p) const {
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() <= width - 1.0 && p.y() <= height - 1.0;
}

std::array<Vec3, 4> PinholeCamera::frustum_corners(double depth) const {
  const double l = -0.5, r = width - 0.5, tp = -0.5, b = height - 0.5;
  return {backproject({l, tp}, depth), backproject({r, tp}, depth), backproject({r, b}, depth),
          backproject({l, b}, depth)};
}

void PinholeCamera::check(const std::string& what) const {
  auto fail = [&](const std::string& reason) { throw Error(what + ": " + reason); };
  if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy) &&
        std::isfinite(k1) && std::isfinite(k2) && R.allFinite() && t.allFinite()))
    fail("non-finite (NaN or inf) camera parameter");
  if (!(fx > 0) || !(fy > 0)) {
    std::ostringstream ss;
    ss << "focal length must be positive (fx = " << fx << ", fy = " << fy << ")";
    fail(ss.str());
  }
  if (width <= 0 || height <= 0)
    fail("image size must be positive (" + std::to_string(width) + "x" +
         std::to_string(height) + ")");
  // A principal point far off the image is a unit or convention error, not
  // an off-centre sensor.
  if (cx < -width || cx > 2.0 * width || cy < -height || cy > 2.0 * height) {
    std::ostringstream ss;
    ss << "principal point (" << cx << ", " << cy << ") is far outside the " << width << "x"
       << height << " image";
    fail(ss.str());
  }
  const double orth = (R * R.transpose() - Mat3::Identity()).norm();
  if (orth > 1e-4 || std::abs(R.determinant() - 1.0) > 1e-4) {
    std::ostringstream ss;
    ss << "R is not a rotation (|R R^T - I| = " << orth << ", det = " << R.determinant() << ")";
    fail(ss.str());
  }
}

}  // namespace meshnbv
