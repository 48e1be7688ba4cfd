// Dense points from known poses: rectified stereo pairs (OpenCV's
// semi-global matching), geometric consistency across pairs, voxel fusion.
#include "meshnbv/eval/dense_backend.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <unordered_map>

#include "meshnbv/enum_names.h"
#include "meshnbv/error.h"
#include "meshnbv/options.h"

namespace fs = std::filesystem;

namespace meshnbv::eval {

constexpr detail::EnumTable<BackendKind, 2> kBackends = {
    {"sparse", BackendKind::Sparse},
    {"dense", BackendKind::Dense},
};

BackendKind parse_backend(const std::string& name) { return detail::parse_enum(name, kBackends, "backend"); }
std::string backend_name(BackendKind kind) { return detail::enum_name(kind, kBackends); }

void DenseOptions::check() const {
  check_option(max_image_size >= 64 && max_image_size <= 20000, "dense max_image_size",
               "in [64, 20000] pixels", max_image_size);
  check_option(partners >= 1 && partners <= 32, "dense partners", "in [1, 32]", partners);
  check_option(min_shared_points >= 1 && min_shared_points <= 100000, "dense min_shared_points",
               "in [1, 100000]", min_shared_points);
  check_option(min_angle >= 0 && min_angle < 90, "dense min_angle", "in [0, 90) degrees", min_angle);
  check_option(max_angle > min_angle && max_angle <= 90, "dense max_angle", "in (min_angle, 90] degrees",
               max_angle);
  check_option(target_angle > 0 && target_angle <= 90, "dense target_angle", "in (0, 90] degrees",
               target_angle);
  check_option(block_size >= 1 && block_size <= 21 && block_size % 2 == 1, "dense block_size",
               "odd, in [1, 21]", block_size);
  check_option(uniqueness >= 0 && uniqueness <= 100, "dense uniqueness", "in [0, 100] percent", uniqueness);
  check_option(min_texture >= 0 && min_texture <= 255, "dense min_texture", "in [0, 255] grey levels",
               min_texture);
  check_option(min_agreeing >= 1 && min_agreeing <= partners, "dense min_agreeing", "in [1, partners]",
               min_agreeing);
  check_option(consistency > 0 && consistency <= 100, "dense consistency", "in (0, 100] pixels", consistency);
  check_option(pixel_step >= 1 && pixel_step <= 64, "dense pixel_step", "in [1, 64]", pixel_step);
  check_option(max_points >= 100 && max_points <= 100000000, "dense max_points", "in [100, 1e8]", max_points);
}

PinholeCamera resized_camera(const PinholeCamera& c, int width, int height) {
  if (c.width == width && c.height == height) return c;
  PinholeCamera s = c;
  const double kx = double(width) / c.width, ky = double(height) / c.height;
  s.width = width;
  s.height = height;
  s.fx *= kx;
  s.fy *= ky;
  s.skew *= kx;
  s.cx = (c.cx + 0.5) * kx - 0.5;
  s.cy = (c.cy + 0.5) * ky - 0.5;
  return s;
}

namespace {

// The size stereo runs at: the longer side at most max_image_size.
cv::Size working_size(const PinholeCamera& c, int max_image_size) {
  const double s = std::min(1.0, double(max_image_size) / double(std::max(c.width, c.height)));
  return {std::max(2, int(std::lround(c.width * s))), std::max(2, int(std::lround(c.height * s)))};
}

cv::Mat grey_mat(const Image& image) {
  cv::Mat m(image.height(), image.width(), image.channels() == 1 ? CV_8UC1 : CV_8UC3,
            const_cast<std::uint8_t*>(image.data()));
  cv::Mat grey;
  if (image.channels() == 1)
    grey = m.clone();
  else
    cv::cvtColor(m, grey, cv::COLOR_RGB2GRAY);
  return grey;
}

// The rectified pair in a canonical orientation: the disparity runs along
// +a (columns) with the match in `other` at a - d, as StereoSGBM wants.
struct PairGeometry {
  Mat3 R1, R2;            // camera -> rectified frame, per camera
  double fx = 0, fy = 0;  // rectified intrinsics (shared)
  double cx1 = 0, cy1 = 0, cx2 = 0, cy2 = 0;
  double baseline = 0;  // |T| along the rectified axis
  // Canonical disparity of a point at depth Z of the rectified frame:
  // f * baseline / Z + offset (the principal points differ along the axis).
  double offset = 0;
  bool vertical = false;  // the baseline runs along the rectified y axis
  bool flip = false;      // the other camera lies on the negative side
  int rect_w = 0, rect_h = 0;
  int canon_w() const { return vertical ? rect_h : rect_w; }
  int canon_h() const { return vertical ? rect_w : rect_h; }
  double f() const { return vertical ? fy : fx; }
  // Canonical pixel -> rectified pixel, and back.
  void to_rect(double a, double b, double* u, double* v) const {
    if (!vertical) {
      *u = flip ? rect_w - 1 - a : a;
      *v = b;
    } else {
      *v = flip ? rect_h - 1 - a : a;
      *u = b;
    }
  }
  void to_canon(double u, double v, double* a, double* b) const {
    if (!vertical) {
      *a = flip ? rect_w - 1 - u : u;
      *b = v;
    } else {
      *a = flip ? rect_h - 1 - v : v;
      *b = u;
    }
  }
};

Mat3 from_cv(const cv::Mat& m) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m.at<double>(i, j);
  return r;
}

PairGeometry rectify(const PinholeCamera& a, const PinholeCamera& b) {
  const Mat3 R = b.R * a.R.transpose();
  const Vec3 T = b.t - R * a.t;
  if (!(T.norm() > 1e-12 * (1.0 + a.t.norm() + b.t.norm())))
    throw Error("the two views share their centre: no stereo baseline");
  cv::Mat Ka = (cv::Mat_<double>(3, 3) << a.fx, 0, a.cx, 0, a.fy, a.cy, 0, 0, 1);
  cv::Mat Kb = (cv::Mat_<double>(3, 3) << b.fx, 0, b.cx, 0, b.fy, b.cy, 0, 0, 1);
  cv::Mat Rcv(3, 3, CV_64F), Tcv(3, 1, CV_64F);
  for (int i = 0; i < 3; ++i) {
    Tcv.at<double>(i) = T(i);
    for (int j = 0; j < 3; ++j) Rcv.at<double>(i, j) = R(i, j);
  }
  cv::Mat R1, R2, P1, P2, Q;
  const cv::Mat no_lens = cv::Mat::zeros(1, 5, CV_64F);
  cv::stereoRectify(Ka, no_lens, Kb, no_lens, cv::Size(a.width, a.height), Rcv, Tcv, R1, R2, P1, P2, Q, 0, -1,
                    cv::Size(a.width, a.height));
  PairGeometry g;
  g.R1 = from_cv(R1);
  g.R2 = from_cv(R2);
  g.fx = P1.at<double>(0, 0);
  g.fy = P1.at<double>(1, 1);
  g.cx1 = P1.at<double>(0, 2);
  g.cy1 = P1.at<double>(1, 2);
  g.cx2 = P2.at<double>(0, 2);
  g.cy2 = P2.at<double>(1, 2);
  g.rect_w = a.width;
  g.rect_h = a.height;
  const double tx = P2.at<double>(0, 3) / g.fx, ty = P2.at<double>(1, 3) / g.fy;
  g.vertical = std::abs(ty) > std::abs(tx);
  const double t = g.vertical ? ty : tx;
  g.flip = t > 0;  // the other camera's centre lies at -t on the rectified axis
  g.baseline = std::abs(t);
  const double shift = g.vertical ? g.cy1 - g.cy2 : g.cx1 - g.cx2;
  g.offset = g.flip ? -shift : shift;
  if (!(g.fx > 0 && g.fy > 0 && g.baseline > 0 && std::isfinite(g.baseline)))
    throw Error("the pair could not be rectified");
  return g;
}

// Maps of a canonical image of camera `cam` (rectification rotation `Rk`,
// principal point cx, cy): for each canonical pixel, where to sample the
// camera's image (-1 where the ray points backwards).
void canonical_maps(const PairGeometry& g, const PinholeCamera& cam, const Mat3& Rk, double cx, double cy,
                    cv::Mat* map_x, cv::Mat* map_y) {
  *map_x = cv::Mat(g.canon_h(), g.canon_w(), CV_32F);
  *map_y = cv::Mat(g.canon_h(), g.canon_w(), CV_32F);
  const Mat3 Rt = Rk.transpose();
  for (int bb = 0; bb < g.canon_h(); ++bb) {
    float* mx = map_x->ptr<float>(bb);
    float* my = map_y->ptr<float>(bb);
    for (int aa = 0; aa < g.canon_w(); ++aa) {
      double u, v;
      g.to_rect(aa, bb, &u, &v);
      const Vec3 ray = Rt * Vec3((u - cx) / g.fx, (v - cy) / g.fy, 1.0);
      mx[aa] = my[aa] = -1.0f;
      if (ray.z() <= 1e-9) continue;
      const Vec2 px = cam.to_pixel(cam.distort(Vec2(ray.x() / ray.z(), ray.y() / ray.z())));
      if (!px.allFinite() || std::abs(px.x()) > 1e7 || std::abs(px.y()) > 1e7) continue;
      mx[aa] = float(px.x());
      my[aa] = float(px.y());
    }
  }
}

// The disparity range (canonical pixels) of scene depths [zmin, zmax]
// along the reference's axis, sampled over the reference image.
std::pair<double, double> disparity_range(const PairGeometry& g, const PinholeCamera& ref, double zmin,
                                          double zmax, const std::vector<Vec3>& points) {
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) {
      const Vec2 px((ref.width - 1) * i / 8.0, (ref.height - 1) * j / 8.0);
      for (double z : {zmin, zmax}) {
        Vec2 n;
        if (!ref.try_undistort(ref.from_pixel(px), &n)) continue;
        const Vec3 x_rect = g.R1 * (Vec3(n.x(), n.y(), 1.0) * z);
        if (x_rect.z() <= 0) continue;
        const double d = g.f() * g.baseline / x_rect.z() + g.offset;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
  if (!(hi >= lo)) throw Error("the depth range lies behind the rectified pair");
  // Where the scene's points are: their disparities (2nd to 98th
  // percentile) widened by a quarter of their spread and 4 pixels on each
  // side, within the range of the depth bounds over the whole image.
  std::vector<double> d;
  for (const Vec3& X : points) {
    const Vec3 x_rect = g.R1 * ref.world_to_camera(X);
    if (x_rect.z() > 0) d.push_back(g.f() * g.baseline / x_rect.z() + g.offset);
  }
  if (d.size() >= 10) {
    std::sort(d.begin(), d.end());
    const double p_lo = d[std::size_t(0.02 * double(d.size() - 1))];
    const double p_hi = d[std::size_t(std::ceil(0.98 * double(d.size() - 1)))];
    const double margin = 0.25 * (p_hi - p_lo) + 4.0;
    lo = std::max(lo, p_lo - margin);
    hi = std::min(hi, p_hi + margin);
    if (!(hi > lo)) throw Error("the scene's points lie outside the depth range");
  }
  return {lo, hi};
}

// SGBM's disparity range from the geometric one: rounded outwards (so a
// slightly different range reuses the cached map) and bounded.
void sgbm_range(double lo, double hi, int* min_disparity, int* num_disparities) {
  const int kMax = 512;
  if (!(lo > -1e6 && hi < 1e6))
    throw Error("the depth range gives disparities beyond a million pixels (a degenerate pair)");
  int mn = int(std::floor(lo)) - 2;
  mn = int(std::floor(mn / 8.0)) * 8;
  int count = int(std::ceil(hi)) + 2 - mn;
  count = std::max(16, int(std::ceil(count / 16.0)) * 16);
  if (count > kMax)
    throw Error("the depth range spans " + std::to_string(count) + " pixels of disparity (at most " +
                std::to_string(kMax) + ")");
  *min_disparity = mn;
  *num_disparities = count;
}

}  // namespace

DepthMap stereo_depth(const PinholeCamera& ref, const Image& ref_image, const PinholeCamera& other,
                      const Image& other_image, double min_depth, double max_depth,
                      const DenseOptions& options, const std::string& disparity_png,
                      const std::vector<Vec3>& scene_points) {
  if (!(min_depth > 0 && max_depth > min_depth && std::isfinite(max_depth)))
    throw Error("stereo: empty depth range [" + std::to_string(min_depth) + ", " + std::to_string(max_depth) +
                "]");
  const PairGeometry g = rectify(ref, other);
  const auto [dlo, dhi] = disparity_range(g, ref, min_depth, max_depth, scene_points);
  int min_disp = 0, num_disp = 0;
  sgbm_range(dlo, dhi, &min_disp, &num_disp);

  cv::Mat mx1, my1, mx2, my2;
  canonical_maps(g, ref, g.R1, g.cx1, g.cy1, &mx1, &my1);
  canonical_maps(g, other, g.R2, g.cx2, g.cy2, &mx2, &my2);
  // Valid canonical pixels: inside the source image, away from its border
  // by half a block (the matcher's window must not see the black frame).
  auto valid_mask = [&](const cv::Mat& mx, const cv::Mat& my, int w, int h) {
    cv::Mat ones(h, w, CV_8U, cv::Scalar(255)), mask;
    cv::remap(ones, mask, mx, my, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
    const int r = options.block_size / 2 + 1;
    cv::erode(mask, mask, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1)));
    return mask;
  };
  const cv::Mat mask1 = valid_mask(mx1, my1, ref.width, ref.height);
  const cv::Mat mask2 = valid_mask(mx2, my2, other.width, other.height);

  cv::Mat disparity;  // CV_16S, disparity * 16
  const int invalid = (min_disp - 1) * 16;
  if (!disparity_png.empty() && fs::exists(disparity_png)) {
    const cv::Mat stored = cv::imread(disparity_png, cv::IMREAD_UNCHANGED);
    if (stored.type() == CV_16UC1 && stored.cols == g.canon_w() && stored.rows == g.canon_h()) {
      stored.convertTo(disparity, CV_16S, 1.0, double(invalid));
    }
  }
  if (disparity.empty()) {
    if (ref_image.width() != ref.width || ref_image.height() != ref.height ||
        other_image.width() != other.width || other_image.height() != other.height)
      throw Error("stereo: an image does not have its camera's size");
    cv::Mat c1, c2;
    cv::remap(grey_mat(ref_image), c1, mx1, my1, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::remap(grey_mat(other_image), c2, mx2, my2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    const int b = options.block_size;
    cv::Ptr<cv::StereoSGBM> sgbm =
        cv::StereoSGBM::create(min_disp, num_disp, b, 8 * b * b, 32 * b * b, 1, 63, options.uniqueness, 100,
                               2, cv::StereoSGBM::MODE_SGBM);
    sgbm->compute(c1, c2, disparity);
    // No depth where the reference's window holds no texture (the standard
    // deviation of its grey levels below min_texture): the matcher only
    // propagates its neighbours' disparity there (sky, blank walls).
    if (options.min_texture > 0) {
      cv::Mat f, mean, mean_sq;
      c1.convertTo(f, CV_32F);
      const cv::Size window(options.block_size, options.block_size);
      cv::boxFilter(f, mean, CV_32F, window);
      cv::boxFilter(f.mul(f), mean_sq, CV_32F, window);
      const float min_var = float(options.min_texture * options.min_texture);
      for (int y = 0; y < disparity.rows; ++y)
        for (int x = 0; x < disparity.cols; ++x)
          if (mean_sq.at<float>(y, x) - mean.at<float>(y, x) * mean.at<float>(y, x) < min_var)
            disparity.at<short>(y, x) = short(invalid);
    }
    if (!disparity_png.empty()) {
      cv::Mat stored;
      disparity.convertTo(stored, CV_16U, 1.0, -double(invalid));
      const std::string tmp = disparity_png + ".tmp.png";
      fs::create_directories(fs::path(disparity_png).parent_path());
      if (cv::imwrite(tmp, stored, {cv::IMWRITE_PNG_COMPRESSION, 1})) fs::rename(tmp, disparity_png);
    }
  }

  DepthMap out;
  out.width = ref.width;
  out.height = ref.height;
  out.depth.assign(std::size_t(ref.width) * std::size_t(ref.height), 0.0f);
  out.k = 1.0 / (g.f() * g.baseline);
  const int cw = g.canon_w(), ch = g.canon_h();
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      Vec2 n;
      if (!ref.try_undistort(ref.from_pixel(Vec2(x, y)), &n)) continue;
      const Vec3 ray = g.R1 * Vec3(n.x(), n.y(), 1.0);
      if (ray.z() <= 1e-9) continue;
      double a, b;
      g.to_canon(g.fx * ray.x() / ray.z() + g.cx1, g.fy * ray.y() / ray.z() + g.cy1, &a, &b);
      const int ia = int(std::lround(a)), ib = int(std::lround(b));
      if (ia < 0 || ib < 0 || ia >= cw || ib >= ch || !mask1.at<std::uint8_t>(ib, ia)) continue;
      const short raw = disparity.at<short>(ib, ia);
      if (raw <= invalid) continue;
      const double d = raw / 16.0;
      const int ia2 = int(std::lround(a - d));
      if (d - g.offset <= 0 || ia2 < 0 || ia2 >= cw || !mask2.at<std::uint8_t>(ib, ia2)) continue;
      const double z = g.f() * g.baseline / (d - g.offset) / ray.z();
      if (z >= min_depth && z <= max_depth)
        out.depth[std::size_t(y) * std::size_t(ref.width) + std::size_t(x)] = float(z);
    }
  return out;
}

namespace {

double median_of(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double quantile_of(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

// An exception's text on one line (OpenCV's end in a newline).
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

std::string hex64(std::uint64_t h) {
  char b[17];
  std::snprintf(b, sizeof(b), "%016llx", static_cast<unsigned long long>(h));
  return b;
}

// FNV-1a: a stable hash (std::hash is not stable across builds).
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::string camera_key(const PinholeCamera& c) {
  std::ostringstream ss;
  ss.precision(17);
  ss << c.fx << " " << c.fy << " " << c.cx << " " << c.cy << " " << c.width << " " << c.height << " "
     << int(c.lens) << " " << c.k1 << " " << c.k2 << " " << c.k3 << " " << c.k4 << " " << c.k5 << " " << c.k6
     << " " << c.p1 << " " << c.p2 << " " << c.skew;
  for (int i = 0; i < 3; ++i) {
    ss << " " << c.t(i);
    for (int j = 0; j < 3; ++j) ss << " " << c.R(i, j);
  }
  return ss.str();
}

std::string file_key(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  const auto time = fs::last_write_time(path, ec).time_since_epoch().count();
  return fs::absolute(path).lexically_normal().string() + " " + std::to_string(size) + " " +
         std::to_string(time);
}

// A partner of a reference view and what is known of the pair.
struct Partner {
  int view = -1;
  double score = 0;
};

struct ViewPlan {
  int view = -1;
  double zmin = 0, zmax = 0;
  std::vector<Vec3> points;  // sparse points the view sees
  std::vector<Partner> partners;
};

// Partners and depth range of each selected view, from the sparse points.
std::vector<ViewPlan> plan_views(const std::vector<View>& views, const std::vector<int>& selected,
                                 const std::vector<SparsePoint>& sparse, const DenseOptions& o,
                                 std::vector<std::string>* failures) {
  std::vector<char> is_selected(views.size(), 0);
  for (int i : selected) is_selected[std::size_t(i)] = 1;
  std::vector<std::vector<std::size_t>> seen_by(views.size());
  for (std::size_t p = 0; p < sparse.size(); ++p)
    for (int v : sparse[p].views)
      if (v >= 0 && std::size_t(v) < views.size() && is_selected[std::size_t(v)])
        seen_by[std::size_t(v)].push_back(p);
  const double deg = 180.0 / M_PI;
  std::vector<ViewPlan> plans;
  for (int r : selected) {
    const View& vr = views[std::size_t(r)];
    ViewPlan plan;
    plan.view = r;
    std::vector<double> depths;
    std::map<int, std::vector<double>> angles;  // partner -> triangulation angles of shared points
    for (std::size_t p : seen_by[std::size_t(r)]) {
      const Vec3& X = sparse[p].position;
      const double z = vr.camera.depth(X);
      if (z > 0) {
        depths.push_back(z);
        plan.points.push_back(X);
      }
      const Vec3 to_r = (vr.camera.center() - X).normalized();
      for (int q : sparse[p].views)
        if (q != r && q >= 0 && std::size_t(q) < views.size() && is_selected[std::size_t(q)]) {
          const Vec3 to_q = (views[std::size_t(q)].camera.center() - X).normalized();
          angles[q].push_back(std::acos(std::clamp(to_r.dot(to_q), -1.0, 1.0)) * deg);
        }
    }
    if (int(depths.size()) < o.min_shared_points) {
      failures->push_back("view " + vr.label + ": " + std::to_string(depths.size()) +
                          " sparse points, too few for a depth range");
      continue;
    }
    plan.zmin = 0.8 * quantile_of(depths, 0.02);
    plan.zmax = 1.25 * quantile_of(depths, 0.98);
    for (const auto& [q, a] : angles) {
      if (int(a.size()) < o.min_shared_points) continue;
      const double angle = median_of(a);
      if (angle < o.min_angle || angle > o.max_angle) continue;
      const double w = std::min(1.0, angle / o.target_angle);
      plan.partners.push_back({q, double(a.size()) * w * w});
    }
    std::sort(plan.partners.begin(), plan.partners.end(), [](const Partner& a, const Partner& b) {
      return a.score > b.score || (a.score == b.score && a.view < b.view);
    });
    if (int(plan.partners.size()) > o.partners) plan.partners.resize(std::size_t(o.partners));
    if (int(plan.partners.size()) < o.min_agreeing) {
      failures->push_back("view " + vr.label + ": " + std::to_string(plan.partners.size()) +
                          " stereo partners (needs " + std::to_string(o.min_agreeing) + ")");
      continue;
    }
    plans.push_back(plan);
  }
  return plans;
}

// Working-size grey images of the views, decoded once per call.
class WorkingImages {
 public:
  WorkingImages(const std::vector<View>& views, int max_size) : views_(views), max_size_(max_size) {}
  std::shared_ptr<const Image> get(int v) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = images_.find(v);
      if (it != images_.end()) return it->second;
    }
    const View& view = views_[std::size_t(v)];
    const Image full = load_view_image(view)->to_8bit();  // SGBM takes 8 bits
    const cv::Size size = working_size(view.camera, max_size_);
    cv::Mat grey = grey_mat(full), small;
    if (size.width != grey.cols || size.height != grey.rows)
      cv::resize(grey, small, size, 0, 0, cv::INTER_AREA);
    else
      small = grey;
    auto image = std::make_shared<Image>(size.width, size.height, 1);
    for (int y = 0; y < size.height; ++y)
      std::copy(small.ptr<std::uint8_t>(y), small.ptr<std::uint8_t>(y) + size.width, image->pixel(0, y));
    std::lock_guard<std::mutex> lock(mutex_);
    images_[v] = image;
    return image;
  }

 private:
  const std::vector<View>& views_;
  int max_size_;
  std::mutex mutex_;
  std::map<int, std::shared_ptr<const Image>> images_;
};

// A view's depth map after the consistency check across its pairs.
struct FusedView {
  PinholeCamera camera;                 // at the working size
  std::vector<int> partners;            // views of the pairs
  std::vector<float> depth;             // 0 = none
  std::vector<float> tolerance;         // consistency tolerance of the depth
  std::vector<std::uint32_t> agreeing;  // bit m: partner m agreed
};

struct FusedPoint {
  Vec3 position;
  std::vector<int> views;
};

struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
    std::uint64_t h = 1469598103934665603ULL;
    for (std::int64_t v : c) h = (h ^ std::uint64_t(v)) * 1099511628211ULL;
    return std::size_t(h ^ (h >> 29));
  }
};

// Points on a voxel grid of `cell`: mean position, union of views.
std::vector<SparsePoint> voxel_merge(const std::vector<FusedPoint>& raw, double cell) {
  std::unordered_map<std::array<std::int64_t, 3>, std::size_t, CellHash> index;
  std::vector<SparsePoint> out;
  std::vector<double> counts;
  index.reserve(raw.size());
  for (const FusedPoint& p : raw) {
    const std::array<std::int64_t, 3> key = {std::int64_t(std::floor(p.position.x() / cell)),
                                             std::int64_t(std::floor(p.position.y() / cell)),
                                             std::int64_t(std::floor(p.position.z() / cell))};
    auto [it, inserted] = index.emplace(key, out.size());
    if (inserted) {
      out.push_back({Vec3::Zero(), {}});
      counts.push_back(0);
    }
    SparsePoint& s = out[it->second];
    s.position += p.position;
    counts[it->second] += 1;
    s.views.insert(s.views.end(), p.views.begin(), p.views.end());
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].position /= counts[i];
    std::sort(out[i].views.begin(), out[i].views.end());
    out[i].views.erase(std::unique(out[i].views.begin(), out[i].views.end()), out[i].views.end());
  }
  return out;
}

}  // namespace

std::vector<SparsePoint> dense_points(const std::vector<View>& views, const std::vector<int>& selected,
                                      const std::vector<SparsePoint>& sparse, const std::string& cache_dir,
                                      const DenseOptions& o, DenseStats* stats_out,
                                      const ProgressCallback& progress) {
  o.check();
  const auto t0 = std::chrono::steady_clock::now();
  DenseStats stats;
  for (int v : selected)
    if (v < 0 || std::size_t(v) >= views.size()) throw Error("dense: view index out of range");
  const std::vector<ViewPlan> plans = plan_views(views, selected, sparse, o, &stats.failures);
  WorkingImages images(views, o.max_image_size);
  std::mutex mutex;
  std::vector<FusedView> fused(plans.size());
  std::atomic<std::size_t> done{0}, computed{0}, pairs{0}, accepted{0};
  const std::string key_params = "sgbm-v1 " + std::to_string(o.max_image_size) + " " +
                                 std::to_string(o.block_size) + " " + std::to_string(o.uniqueness) + " " +
                                 std::to_string(o.min_texture);
  tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
    const ViewPlan& plan = plans[i];
    const View& vr = views[std::size_t(plan.view)];
    const cv::Size size_r = working_size(vr.camera, o.max_image_size);
    const PinholeCamera cam_r = resized_camera(vr.camera, size_r.width, size_r.height);
    std::vector<DepthMap> maps;
    std::vector<int> partner_views;
    for (const Partner& partner : plan.partners) {
      const View& vp = views[std::size_t(partner.view)];
      const cv::Size size_p = working_size(vp.camera, o.max_image_size);
      const PinholeCamera cam_p = resized_camera(vp.camera, size_p.width, size_p.height);
      try {
        // The cache key: both images and cameras, the rounded disparity range, the matcher.
        const PairGeometry g = rectify(cam_r, cam_p);
        const auto [lo, hi] = disparity_range(g, cam_r, plan.zmin, plan.zmax, plan.points);
        int mn = 0, num = 0;
        sgbm_range(lo, hi, &mn, &num);
        const std::string key = key_params + "\n" + file_key(vr.image_path) + "\n" + camera_key(cam_r) +
                                "\n" + file_key(vp.image_path) + "\n" + camera_key(cam_p) + "\n" +
                                std::to_string(mn) + " " + std::to_string(num);
        const std::string png = (fs::path(cache_dir) / (hex64(fnv1a(key)) + ".png")).string();
        // A cache entry that does not read back is matched again.
        DepthMap map;
        bool matched = false;
        if (fs::exists(png)) {
          try {
            map = stereo_depth(cam_r, Image(), cam_p, Image(), plan.zmin, plan.zmax, o, png, plan.points);
          } catch (const Error&) {
            std::error_code ec;
            fs::remove(png, ec);
          }
        }
        if (map.depth.empty()) {
          const auto ir = images.get(plan.view), ip = images.get(partner.view);
          map = stereo_depth(cam_r, *ir, cam_p, *ip, plan.zmin, plan.zmax, o, png, plan.points);
          matched = true;
        }
        maps.push_back(std::move(map));
        partner_views.push_back(partner.view);
        if (matched) ++computed;
        ++pairs;
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(mutex);
        stats.failures.push_back("pair " + vr.label + "-" + vp.label + ": " + one_line(e.what()));
      }
    }
    const std::size_t need = std::size_t(o.min_agreeing);
    if (maps.size() < need) {
      std::lock_guard<std::mutex> lock(mutex);
      stats.failures.push_back("view " + vr.label + ": " + std::to_string(maps.size()) +
                               " depth maps (needs " + std::to_string(need) + ")");
      return;
    }
    // Geometric consistency across the pairs: the view's fused depth map.
    FusedView& fv = fused[i];
    fv.camera = cam_r;
    fv.partners = partner_views;
    const std::size_t npx = std::size_t(cam_r.width) * std::size_t(cam_r.height);
    fv.depth.assign(npx, 0.0f);
    fv.tolerance.assign(npx, 0.0f);
    fv.agreeing.assign(npx, 0u);
    std::vector<std::pair<float, std::size_t>> z;
    std::size_t count = 0;
    for (std::size_t px = 0; px < npx; ++px) {
      z.clear();
      for (std::size_t m = 0; m < maps.size(); ++m)
        if (const float d = maps[m].depth[px]; d > 0) z.emplace_back(d, m);
      if (z.size() < need) continue;
      std::sort(z.begin(), z.end());
      const double med = z[z.size() / 2].first;
      double sum = 0, tol = 0;
      std::uint32_t mask = 0;
      std::size_t agreeing = 0;
      for (const auto& [d, m] : z) {
        const double t = o.consistency * med * med * maps[m].k;
        if (std::abs(d - med) <= t) {
          sum += d;
          tol += t;
          mask |= 1u << m;
          ++agreeing;
        }
      }
      if (agreeing < need) continue;
      fv.depth[px] = float(sum / double(agreeing));
      fv.tolerance[px] = float(tol / double(agreeing));
      fv.agreeing[px] = mask;
      ++count;
    }
    accepted += count;
    report_progress(progress, 0.8 * double(++done) / double(plans.size()), "dense");
  });
  stats.pairs = pairs;
  stats.pairs_computed = computed;
  stats.depth_pixels = accepted;
  const auto t1 = std::chrono::steady_clock::now();
  // Every view's depths against the other views' (Merrell et al. 2007): a
  // view whose depth map holds the same depth supports a point, one that
  // saw something farther away along the point's ray contradicts it (the
  // point lies in space that view saw through). Points need more support
  // than contradiction; their views are the reference, its agreeing pairs
  // and the supporting views.
  std::vector<std::vector<FusedPoint>> per_view(plans.size());
  std::vector<double> footprints(plans.size(), 0.0);
  std::atomic<std::size_t> contradicted{0};
  tbb::parallel_for(std::size_t(0), plans.size(), [&](std::size_t i) {
    const FusedView& fv = fused[i];
    if (fv.depth.empty()) return;
    const PinholeCamera& cam = fv.camera;
    std::vector<double> depths_used;
    std::size_t rejected = 0;
    for (int y = 0; y < cam.height; y += o.pixel_step)
      for (int x = 0; x < cam.width; x += o.pixel_step) {
        const std::size_t px = std::size_t(y) * std::size_t(cam.width) + std::size_t(x);
        const float d = fv.depth[px];
        if (d <= 0) continue;
        FusedPoint fp;
        fp.position = cam.backproject(Vec2(x, y), d);
        if (!fp.position.allFinite()) continue;
        fp.views.push_back(plans[i].view);
        for (std::size_t m = 0; m < fv.partners.size(); ++m)
          if (fv.agreeing[px] & (1u << m)) fp.views.push_back(fv.partners[m]);
        int support = 0, conflict = 0;
        for (std::size_t j = 0; j < fused.size(); ++j) {
          if (j == i || fused[j].depth.empty()) continue;
          const FusedView& other = fused[j];
          Vec2 q;
          double zq = 0;
          if (!other.camera.project(fp.position, &q, &zq)) continue;
          const int qx = int(std::lround(q.x())), qy = int(std::lround(q.y()));
          if (qx < 0 || qy < 0 || qx >= other.camera.width || qy >= other.camera.height) continue;
          const std::size_t qp = std::size_t(qy) * std::size_t(other.camera.width) + std::size_t(qx);
          const double dq = other.depth[qp];
          if (dq <= 0) continue;
          // Tolerance: the seen depth's own, and the point's carried over
          // by the ratio of depths (z^2 scaling).
          const double tol =
              std::max(double(other.tolerance[qp]), double(fv.tolerance[px]) * (zq * zq) / (double(d) * d));
          if (std::abs(zq - dq) <= tol) {
            ++support;
            fp.views.push_back(plans[j].view);
          } else if (zq < dq - tol) {
            ++conflict;
          }
        }
        if (conflict > support) {
          ++rejected;
          continue;
        }
        std::sort(fp.views.begin(), fp.views.end());
        fp.views.erase(std::unique(fp.views.begin(), fp.views.end()), fp.views.end());
        per_view[i].push_back(std::move(fp));
        if ((per_view[i].size() & 15) == 0) depths_used.push_back(d);
      }
    contradicted += rejected;
    footprints[i] = depths_used.empty() ? 0.0 : median_of(depths_used) / cam.fx;
    report_progress(progress, 0.8 + 0.2 * double(++done - plans.size()) / double(plans.size()), "dense");
  });
  stats.contradicted = contradicted;
  std::vector<FusedPoint> raw;
  std::vector<double> fp;
  for (std::size_t i = 0; i < per_view.size(); ++i) {
    if (!per_view[i].empty()) {
      ++stats.views;
      fp.push_back(footprints[i]);
    }
    for (auto& p : per_view[i]) raw.push_back(std::move(p));
  }
  stats.raw_points = raw.size();
  std::vector<SparsePoint> out;
  if (!raw.empty()) {
    double cell = o.pixel_step * median_of(fp);
    if (!(cell > 0)) cell = 1e-9;
    out = voxel_merge(raw, cell);
    while (out.size() > std::size_t(o.max_points)) {
      cell *= 1.05 * std::sqrt(double(out.size()) / double(o.max_points));
      out = voxel_merge(raw, cell);
    }
    stats.voxel = cell;
  }
  stats.points = out.size();
  const auto t2 = std::chrono::steady_clock::now();
  stats.seconds_stereo = std::chrono::duration<double>(t1 - t0).count();
  stats.seconds_fusion = std::chrono::duration<double>(t2 - t1).count();
  std::sort(stats.failures.begin(), stats.failures.end());
  if (stats_out) *stats_out = std::move(stats);
  return out;
}

}  // namespace meshnbv::eval
