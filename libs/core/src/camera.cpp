#include "meshnbv/camera.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
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
  k << fx, skew, cx, 0, fy, cy, 0, 0, 1;
  return k;
}

bool PinholeCamera::has_lens_distortion() const {
  return lens != LensModel::Brown || k1 != 0.0 || k2 != 0.0 || k3 != 0.0 || k4 != 0.0 ||
         k5 != 0.0 || k6 != 0.0 || p1 != 0.0 || p2 != 0.0;
}

void PinholeCamera::clear_lens() {
  lens = LensModel::Brown;
  k1 = k2 = k3 = k4 = k5 = k6 = p1 = p2 = skew = 0.0;
}

std::string PinholeCamera::lens_description() const {
  std::ostringstream out;
  out << std::setprecision(6);
  if (!has_distortion()) return "pinhole";
  out << (lens == LensModel::Fisheye ? "fisheye" : (has_lens_distortion() ? "brown" : "pinhole"));
  const std::pair<const char*, double> params[] = {{"k1", k1}, {"k2", k2}, {"k3", k3},
                                                   {"k4", k4}, {"k5", k5}, {"k6", k6},
                                                   {"p1", p1}, {"p2", p2}, {"skew", skew}};
  for (const auto& [name, value] : params)
    if (value != 0.0) out << ' ' << name << '=' << value;
  return out.str();
}

namespace {

// Brown-Conrady: the distorted point and (optionally) its Jacobian.
Vec2 brown(const PinholeCamera& c, const Vec2& n, Eigen::Matrix2d* J) {
  const double x = n.x(), y = n.y(), r2 = x * x + y * y;
  const double num = 1 + r2 * (c.k1 + r2 * (c.k2 + r2 * c.k3));
  const double den = 1 + r2 * (c.k4 + r2 * (c.k5 + r2 * c.k6));
  const double a = num / den;
  const Vec2 d(x * a + 2 * c.p1 * x * y + c.p2 * (r2 + 2 * x * x),
               y * a + c.p1 * (r2 + 2 * y * y) + 2 * c.p2 * x * y);
  if (J) {
    const double dnum = c.k1 + r2 * (2 * c.k2 + 3 * c.k3 * r2);
    const double dden = c.k4 + r2 * (2 * c.k5 + 3 * c.k6 * r2);
    const double da = (dnum * den - num * dden) / (den * den);  // d a / d r^2
    (*J)(0, 0) = a + 2 * x * x * da + 2 * c.p1 * y + 6 * c.p2 * x;
    (*J)(0, 1) = 2 * x * y * da + 2 * c.p1 * x + 2 * c.p2 * y;
    (*J)(1, 0) = 2 * x * y * da + 2 * c.p1 * x + 2 * c.p2 * y;
    (*J)(1, 1) = a + 2 * y * y * da + 6 * c.p1 * y + 2 * c.p2 * x;
  }
  return d;
}

// Equidistant fisheye: theta_d(theta) and its derivative.
double fisheye_theta_d(const PinholeCamera& c, double th, double* derivative) {
  const double t2 = th * th;
  if (derivative)
    *derivative = 1 + t2 * (3 * c.k1 + t2 * (5 * c.k2 + t2 * (7 * c.k3 + t2 * 9 * c.k4)));
  return th * (1 + t2 * (c.k1 + t2 * (c.k2 + t2 * (c.k3 + t2 * c.k4))));
}

bool converged(double residual, double target) {
  return residual <= kUndistortTolerance * (1 + target);
}

constexpr int kMaxIterations = 100;

bool undistort_fisheye(const PinholeCamera& c, const Vec2& d, Vec2* n) {
  const double td = d.norm();
  if (td == 0) {
    *n = d;
    return true;
  }
  constexpr double kHalfPi = 1.5707963267948966;
  double th = std::min(td, kHalfPi * 0.999);
  for (int i = 0; i < kMaxIterations; ++i) {
    double slope = 0;
    const double f = fisheye_theta_d(c, th, &slope) - td;
    if (converged(std::abs(f), td)) {
      // Beyond 90 degrees the ray points backwards: no z > 0 point sees it.
      if (!(th < kHalfPi) || !(slope > 0)) return false;
      *n = d * (std::tan(th) / td);
      return n->allFinite();
    }
    if (!(slope > 0)) return false;  // past a turning point: not invertible here
    th -= f / slope;
    if (!(th >= 0 && th < kHalfPi)) return false;
  }
  return false;
}

bool undistort_brown(const PinholeCamera& c, const Vec2& d, Vec2* n) {
  Vec2 x = d;
  Eigen::Matrix2d J;
  Vec2 f = brown(c, x, &J) - d;
  const double target = d.norm();
  for (int i = 0; i < kMaxIterations; ++i) {
    if (converged(f.norm(), target)) {
      if (!(J.determinant() > 0)) return false;  // the lens folds over here
      *n = x;
      return true;
    }
    const double det = J.determinant();
    if (!(det > 0) || !std::isfinite(det)) return false;
    const Vec2 step = J.inverse() * f;
    // Damped: halve the step until the residual shrinks.
    double scale = 1;
    for (int h = 0; h < 30; ++h, scale *= 0.5) {
      const Vec2 trial = x - scale * step;
      Eigen::Matrix2d Jt;
      const Vec2 ft = brown(c, trial, &Jt) - d;
      if (ft.allFinite() && ft.norm() < f.norm()) {
        x = trial;
        f = ft;
        J = Jt;
        break;
      }
      if (h == 29) return false;
    }
  }
  return false;
}

}  // namespace

Vec2 PinholeCamera::distort(const Vec2& n) const {
  if (!has_lens_distortion()) return n;
  if (lens == LensModel::Fisheye) {
    const double r = n.norm();
    if (r == 0) return n;
    return n * (fisheye_theta_d(*this, std::atan(r), nullptr) / r);
  }
  return brown(*this, n, nullptr);
}

bool PinholeCamera::try_undistort(const Vec2& d, Vec2* n) const {
  if (!has_lens_distortion()) {
    *n = d;
    return true;
  }
  if (!d.allFinite()) return false;
  return lens == LensModel::Fisheye ? undistort_fisheye(*this, d, n) : undistort_brown(*this, d, n);
}

Vec2 PinholeCamera::undistort(const Vec2& d) const {
  Vec2 n;
  if (try_undistort(d, &n)) return n;
  std::ostringstream ss;
  ss << "lens undistortion did not converge at normalised (" << d.x() << ", " << d.y() << ") ("
     << lens_description() << "): the lens model does not invert there";
  throw Error(ss.str());
}

Vec2 PinholeCamera::to_pixel(const Vec2& d) const {
  return Vec2(fx * d.x() + skew * d.y() + cx, fy * d.y() + cy);
}

Vec2 PinholeCamera::from_pixel(const Vec2& p) const {
  const double y = (p.y() - cy) / fy;
  return Vec2((p.x() - cx - skew * y) / fx, y);
}

bool PinholeCamera::project(const Vec3& X, Vec2* pixel, double* depth_out) const {
  const Vec3 xc = world_to_camera(X);
  if (!(xc.z() > 0)) return false;
  *pixel = to_pixel(distort(Vec2(xc.x() / xc.z(), xc.y() / xc.z())));
  if (depth_out) *depth_out = xc.z();
  return true;
}

Vec3 PinholeCamera::backproject(const Vec2& pixel, double depth) const {
  const Vec2 n = undistort(from_pixel(pixel));
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
        std::isfinite(k1) && std::isfinite(k2) && std::isfinite(k3) && std::isfinite(k4) &&
        std::isfinite(k5) && std::isfinite(k6) && std::isfinite(p1) && std::isfinite(p2) &&
        std::isfinite(skew) && R.allFinite() && t.allFinite()))
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
  check_lens(what);
}

void PinholeCamera::check_lens(const std::string& what) const {
  if (lens == LensModel::Fisheye && (k5 != 0.0 || k6 != 0.0 || p1 != 0.0 || p2 != 0.0))
    throw Error(what + ": the fisheye model takes k1..k4 only (k5, k6, p1, p2 must be 0)");
  if (!has_lens_distortion()) return;
  // The lens must invert over the whole image: a 9x9 grid, corners included.
  constexpr int kGrid = 9;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec2 pixel(-0.5 + width * double(i) / (kGrid - 1), -0.5 + height * double(j) / (kGrid - 1));
      Vec2 n;
      if (!try_undistort(from_pixel(pixel), &n)) {
        std::ostringstream ss;
        ss << what << ": the lens model (" << lens_description()
           << ") does not invert at pixel (" << pixel.x() << ", " << pixel.y()
           << "): undistortion does not converge or the mapping folds over there";
        throw Error(ss.str());
      }
    }
}

}  // namespace meshnbv
