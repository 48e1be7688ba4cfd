#include "meshnbv/visualize.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "meshnbv/error.h"
#include "meshnbv/pri.h"

namespace meshnbv {
namespace {

// The image's pixels as an OpenCV matrix (RGB order kept: colours are given
// to OpenCV in the same order).
cv::Mat as_mat(Image& image) {
  if (image.bits() != 8) throw Error("drawing needs an 8-bit image (Image::to_8bit)");
  return cv::Mat(image.height(), image.width(), image.channels() == 1 ? CV_8UC1 : CV_8UC3, image.data());
}

cv::Scalar rgb(const Rgb8& c) { return cv::Scalar(c[0], c[1], c[2]); }

// Segment a-b in world coordinates, clipped at z = near in the camera frame,
// then projected (pinhole, no distortion). False if entirely behind.
bool project_segment(const PinholeCamera& cam, Vec3 a, Vec3 b, cv::Point2d* pa, cv::Point2d* pb) {
  const double near = 1e-3;
  Vec3 ca = cam.world_to_camera(a), cb = cam.world_to_camera(b);
  if (ca.z() < near && cb.z() < near) return false;
  if (ca.z() < near) ca = cb + (ca - cb) * ((cb.z() - near) / (cb.z() - ca.z()));
  if (cb.z() < near) cb = ca + (cb - ca) * ((ca.z() - near) / (ca.z() - cb.z()));
  *pa = cv::Point2d(cam.fx * ca.x() / ca.z() + cam.cx, cam.fy * ca.y() / ca.z() + cam.cy);
  *pb = cv::Point2d(cam.fx * cb.x() / cb.z() + cam.cx, cam.fy * cb.y() / cb.z() + cam.cy);
  return true;
}

void draw_segment(cv::Mat& m, const PinholeCamera& cam, const Vec3& a, const Vec3& b,
                  const cv::Scalar& colour, int thickness) {
  cv::Point2d pa, pb;
  if (!project_segment(cam, a, b, &pa, &pb)) return;
  // Keep coordinates in a range OpenCV's integer line code handles.
  const double lim = 1e5;
  auto clampp = [lim](cv::Point2d p) {
    return cv::Point(int(std::clamp(p.x, -lim, lim) * 16), int(std::clamp(p.y, -lim, lim) * 16));
  };
  cv::line(m, clampp(pa), clampp(pb), colour, thickness, cv::LINE_AA, 4);
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g", v);
  return buf;
}

}  // namespace

PinholeCamera overview_camera(const std::vector<Vec3>& points, double azimuth, double elevation,
                              int width, int height) {
  if (points.empty()) throw Error("overview of nothing");
  BoundingBox box;
  for (const Vec3& p : points) box.extend(p);
  const Vec3 centre = box.center();
  const double az = azimuth * M_PI / 180, el = elevation * M_PI / 180;
  const Vec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const double f = 0.5 * width / std::tan(30 * M_PI / 180);  // 60 degrees across
  auto at = [&](double d) {
    return PinholeCamera::look_at(centre + d * dir, centre, Vec3::UnitZ(), f, f, (width - 1) / 2.0,
                                  (height - 1) / 2.0, width, height);
  };
  auto fits = [&](double d) {
    const PinholeCamera c = at(d);
    for (const Vec3& p : points) {
      Vec2 px;
      if (!c.project(p, &px)) return false;
      if (px.x() < 0.05 * width || px.x() > 0.95 * width || px.y() < 0.05 * height ||
          px.y() > 0.95 * height)
        return false;
    }
    return true;
  };
  double lo = 1e-6 + 0.0, hi = std::max(1e-3, box.diagonal());
  while (!fits(hi) && hi < 1e9) hi *= 2;
  lo = hi / 64;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? hi : lo) = mid;
  }
  return at(hi);
}

void draw_frustums(Image& image, const PinholeCamera& viewer, const std::vector<FrustumOverlay>& frustums) {
  if (image.channels() != 3) throw Error("draw_frustums needs an RGB image");
  cv::Mat m = as_mat(image);
  for (const auto& f : frustums) {
    const Vec3 apex = f.camera.center();
    const auto corners = f.camera.frustum_corners(f.depth);
    const cv::Scalar colour = rgb(f.colour);
    for (int k = 0; k < 4; ++k) {
      draw_segment(m, viewer, apex, corners[std::size_t(k)], colour, f.thickness);
      draw_segment(m, viewer, corners[std::size_t(k)], corners[std::size_t((k + 1) % 4)], colour, f.thickness);
    }
    if (!f.label.empty()) {
      Vec2 px;
      if (viewer.project(corners[0], &px))
        cv::putText(m, f.label, cv::Point(int(px.x()) + 4, int(px.y()) - 4), cv::FONT_HERSHEY_SIMPLEX,
                    0.5, colour, 1, cv::LINE_AA);
    }
  }
}

void draw_color_scale(Image& image, double lo, double hi, const std::string& title) {
  cv::Mat m = as_mat(image);
  const int bar_w = 18, bar_h = std::max(60, image.height() / 3);
  const int x0 = image.width() - bar_w - 95, y0 = 28;
  std::vector<float> values(1);
  for (int y = 0; y < bar_h; ++y) {
    values[0] = float(hi - (hi - lo) * y / double(bar_h - 1));
    const Rgb8 c = pri_colors(values, lo, hi)[0];
    cv::line(m, cv::Point(x0, y0 + y), cv::Point(x0 + bar_w, y0 + y), rgb(c), 1);
  }
  cv::rectangle(m, cv::Rect(x0, y0, bar_w + 1, bar_h), cv::Scalar(40, 40, 40), 1);
  const cv::Scalar ink(20, 20, 20);
  cv::putText(m, title, cv::Point(x0 - 40, y0 - 10), cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1, cv::LINE_AA);
  cv::putText(m, number(hi), cv::Point(x0 + bar_w + 5, y0 + 10), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  cv::putText(m, number(lo), cv::Point(x0 + bar_w + 5, y0 + bar_h), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  const int gy = y0 + bar_h + 10;
  cv::rectangle(m, cv::Rect(x0, gy, bar_w, 12), cv::Scalar(160, 160, 160), cv::FILLED);
  cv::putText(m, "unobserved", cv::Point(x0 + bar_w + 5, gy + 11), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
}

Image histogram_image(const std::vector<float>& values, int bins, int width, int height,
                      const std::string& title) {
  Image img(width, height, 3);
  std::fill(img.data(), img.data() + img.bytes(), std::uint8_t(255));
  cv::Mat m = as_mat(img);
  std::vector<float> v;
  for (float x : values)
    if (!std::isnan(x)) v.push_back(x);
  const cv::Scalar ink(30, 30, 30);
  cv::putText(m, title, cv::Point(10, 18), cv::FONT_HERSHEY_SIMPLEX, 0.5, ink, 1, cv::LINE_AA);
  if (v.empty() || bins < 1) return img;
  const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
  const double lo = *mn, hi = *mx > *mn ? *mx : *mn + 1e-12;
  std::vector<std::size_t> counts(std::size_t(bins), 0);
  for (float x : v) ++counts[std::min(std::size_t(bins) - 1, std::size_t((x - lo) / (hi - lo) * bins))];
  const std::size_t top = *std::max_element(counts.begin(), counts.end());
  const int left = 55, right = width - 15, bottom = height - 35, ceiling = 45;
  cv::line(m, cv::Point(left, bottom), cv::Point(right, bottom), ink, 1);
  cv::line(m, cv::Point(left, bottom), cv::Point(left, ceiling), ink, 1);
  const double bw = double(right - left) / bins;
  std::vector<float> centre(1);
  for (int b = 0; b < bins; ++b) {
    // Bars on a square-root scale, so the long tail of bad faces shows.
    const double h = top ? std::sqrt(double(counts[std::size_t(b)]) / double(top)) : 0;
    centre[0] = float(lo + (b + 0.5) * (hi - lo) / bins);
    const Rgb8 c = pri_colors(centre, lo, hi)[0];
    const int y = bottom - int(h * (bottom - ceiling));
    cv::rectangle(m, cv::Point(left + int(b * bw) + 1, y), cv::Point(left + int((b + 1) * bw) - 1, bottom),
                  rgb(c), cv::FILLED);
  }
  cv::putText(m, number(lo), cv::Point(left - 10, bottom + 18), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  cv::putText(m, number(hi), cv::Point(right - 40, bottom + 18), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  cv::putText(m, std::to_string(top), cv::Point(5, ceiling + 5), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  cv::putText(m, "faces (square-root scale)", cv::Point(width - 200, 18), cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  return img;
}

double coverage(const Image& image, const Vec3& background) {
  const int bg[3] = {int(std::lround(background.x() * 255)), int(std::lround(background.y() * 255)),
                     int(std::lround(background.z() * 255))};
  std::size_t n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      for (int c = 0; c < std::min(3, image.channels()); ++c)
        if (std::abs(int(p[c]) - bg[c]) > 2) {
          ++n;
          break;
        }
    }
  return double(n) / double(std::size_t(image.width()) * image.height());
}

}  // namespace meshnbv
