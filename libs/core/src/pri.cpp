#include "meshnbv/pri.h"
#include "meshnbv/enum_names.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <array>
#include <cstring>
#include <deque>
#include <exception>
#include <filesystem>
#include <numeric>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "meshnbv/options.h"
#include "meshnbv/sampling.h"
#include "x86_simd.h"
#include "meshnbv/error.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/results.h"
#include "percentiles.h"

namespace meshnbv {

constexpr detail::EnumTable<Measure, 3> kMeasures = {
    {"ssd", Measure::SSD},
    {"ncc", Measure::NCC},
    {"offset", Measure::Offset},
};

Measure parse_measure(const std::string& name) {
  return detail::parse_enum(name, kMeasures, "measure");
}

std::string measure_name(Measure measure) {
  return detail::enum_name(measure, kMeasures);
}

void PriOptions::check() const {
  // The ranges are the option table's (options.h): one place for every front end.
  check_options(*this, pri_option_table());
  visibility.check();
}

double ssd_error(const float* a, const float* b, std::size_t n) {
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = double(a[k]) - double(b[k]);
    sum += d * d;
  }
  return n ? sum / double(n) : 0.0;
}

namespace {

struct PatchStats {
  double mean = 0, variance = 0, inv_norm = 0;  // inv_norm = 1 / sqrt(sum (x - mean)^2)
  bool textureless = true;
};

// The sum of term(k) for k < n in four interleaved partial sums (k mod 4)
// added as (s0 + s1) + (s2 + s3): four independent dependency chains
// instead of one, the same bits on every processor and thread count.
// term(k) may also update element k of an array (each k once).
template <class Term>
inline double sum4(std::size_t n, Term term) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    s0 += term(k);
    s1 += term(k + 1);
    s2 += term(k + 2);
    s3 += term(k + 3);
  }
  if (k < n) s0 += term(k++);
  if (k < n) s1 += term(k++);
  if (k < n) s2 += term(k);
  return (s0 + s1) + (s2 + s3);
}

// The sum of term(k) for k < n in order (one chain).
template <class Term>
inline double sum1(std::size_t n, Term term) {
  double s = 0;
  for (std::size_t k = 0; k < n; ++k) s += term(k);
  return s;
}

// Mean and spread of a patch. NCC and the offset measure sum in order:
// their 1 - rho cancels, and summing in four chains moved the error of a
// few near-perfect matches by up to 3e-4 relative. SSD (a sum of
// non-negative terms; the spread only gives the texture) sums in four
// chains: its results move by a few units in the 16th digit, below what
// its float outputs hold.
template <bool kFourChains = false>
PatchStats patch_stats(const float* a, std::size_t n, double min_variance) {
  PatchStats s;
  auto sum = [n](auto term) { return kFourChains ? sum4(n, term) : sum1(n, term); };
  s.mean = sum([&](std::size_t k) { return double(a[k]); }) / double(n);
  const double ss = sum([&](std::size_t k) { return (a[k] - s.mean) * (a[k] - s.mean); });
  s.variance = ss / double(n);
  s.textureless = !(s.variance >= min_variance) || ss <= 0;
  s.inv_norm = s.textureless ? 0.0 : 1.0 / std::sqrt(ss);
  return s;
}

double ncc_from_stats(const float* a, const PatchStats& sa, const float* b, const PatchStats& sb,
                      std::size_t n) {
  double cross = 0;
  for (std::size_t k = 0; k < n; ++k) cross += (a[k] - sa.mean) * (b[k] - sb.mean);
  const double rho = std::clamp(cross * sa.inv_norm * sb.inv_norm, -1.0, 1.0);
  return (1.0 - rho) / 2.0;
}

// The lattice is never contracted to less than half the face (faces a few
// pixels wide keep their centre half).
constexpr double kMaxShrink = 0.5;
// The offset measure's lattice: samples about kOffsetSpacing pixels apart,
// at most kOffsetMaxSide per side.
constexpr double kOffsetSpacing = 1.0;
constexpr int kOffsetMaxSide = 16;
constexpr double kOffsetSpacingPower = 1.5;
// The least residual cost (NCC error) that the offset's precision divides
// by: rho = 0.998; a perfect match is not infinitely precise.
constexpr double kMinResidualCost = 1e-3;
// A sweep whose least cost is at an end counts as evidence of an error
// beyond the range only when its cost falls steadily from the face's own
// position to that end: no step back up by more than this share of the
// whole fall (docs/pri.md, "Steady ends": such ends are where the error
// is beyond the range; wavering ones are failed matches on weak texture).
constexpr double kSteadyRise = 0.1;

double projected_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

// The centroid and the edge midpoints of face f are unoccluded from centre c.
bool interior_unoccluded(const TriangleMesh& mesh, const RayCaster& caster, std::size_t f,
                         const Vec3& c, const PriOptions& o, double abs_eps) {
  const Face& face = mesh.faces[f];
  const Vec3 &a = mesh.vertices[face[0]], &b = mesh.vertices[face[1]], &d = mesh.vertices[face[2]];
  const Vec3 points[4] = {(a + b + d) / 3.0, 0.5 * (a + b), 0.5 * (b + d), 0.5 * (d + a)};
  return caster.segments_clear4(c, points, o.visibility.relative_eps, abs_eps);
}

// `usable`: the cameras (ascending indices into cams) that `vis` holds, in
// its order; null = every camera.
PriFaceViews select_views(const TriangleMesh& mesh, const std::vector<Vec3>& normals,
                       const VertexVisibility& vis, const RayCaster& caster,
                       const std::vector<PinholeCamera>& cams, const std::vector<Vec3>& centres,
                       std::size_t f, const PriOptions& o, double abs_eps, const std::vector<int>* usable) {
  PriFaceViews out;
  struct Candidate {
    int view;
    double angle, area, max_edge, inner;  // inner: distance (px) from the centroid to the nearest edge
  };
  std::vector<Candidate> candidates;
  const Vec3 centroid = mesh.face_centroid(f);
  const Face& face = mesh.faces[f];
  const double min_cosine = std::cos(o.max_incidence_angle * M_PI / 180.0);
  const std::size_t n = usable ? usable->size() : cams.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = usable ? std::size_t((*usable)[k]) : k;
    if (!face_visible(mesh, normals, vis, f, k, centres[i])) continue;
    Vec2 p[3];
    for (int c = 0; c < 3; ++c) cams[i].project(mesh.vertices[face[c]], &p[c]);
    const double cosine = normals[f].dot((centres[i] - centroid).normalized());
    if (cosine < min_cosine) continue;  // grazing view
    if (o.check_interior_occlusion && !interior_unoccluded(mesh, caster, f, centres[i], o, abs_eps))
      continue;
    const double max_edge = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
    const double area = projected_area(p[0], p[1], p[2]);
    // The centroid is a third of each height away from that edge.
    candidates.push_back({int(i), std::acos(std::clamp(cosine, -1.0, 1.0)), area, max_edge,
                          2.0 * area / (3.0 * max_edge)});
  }
  if (o.max_views_per_face > 0 && int(candidates.size()) > o.max_views_per_face) {
    // Smallest incidence angle first; ties by larger projected area, then by index.
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      if (a.angle != b.angle) return a.angle < b.angle;
      return a.area > b.area;
    });
    candidates.resize(std::size_t(o.max_views_per_face));
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.view < b.view; });
  }
  double max_edge = 0;
  for (const auto& c : candidates) {
    out.views.push_back(c.view);
    max_edge = std::max(max_edge, c.max_edge);
    // Contraction that keeps the lattice edge_margin pixels inside the
    // face's projection in this view (the bilinear footprint of a border
    // sample must not reach beyond the face).
    if (o.edge_margin > 0)
      out.shrink = std::max(out.shrink, c.inner > 0 ? o.edge_margin / c.inner : 1.0);
  }
  out.shrink = std::min(out.shrink, kMaxShrink);
  out.samples_per_side = o.samples_per_side > 0
                             ? o.samples_per_side
                             : std::clamp(int(std::ceil(max_edge)), 2, 32);
  if (o.measure != Measure::Offset || candidates.empty()) return out;

  // The offset sweep: the reference is the most frontal view (ties: the
  // larger projection); the step makes the fastest-moving view's projection
  // move offset_range / offset_steps pixels per hypothesis.
  std::size_t ref = 0;
  for (std::size_t k = 1; k < candidates.size(); ++k)
    if (candidates[k].angle < candidates[ref].angle ||
        (candidates[k].angle == candidates[ref].angle && candidates[k].area > candidates[ref].area))
      ref = k;
  out.reference = int(ref);
  const double keep = 1.0 - out.shrink;
  const PinholeCamera& rc = cams[std::size_t(candidates[ref].view)];
  out.pixel = std::max(rc.depth(centroid), 0.0) / rc.fx;
  const Vec3& a = mesh.vertices[face[0]];
  const double h = 1e-3 * std::max({(mesh.vertices[face[1]] - a).norm(), (mesh.vertices[face[2]] - a).norm(), 1e-12});
  double rate = 0;  // pixels per scene unit of offset, fastest view
  for (const auto& c : candidates) {
    Vec2 p0, p1;
    if (cams[std::size_t(c.view)].project(centroid, &p0) &&
        cams[std::size_t(c.view)].project(centroid + h * normals[f], &p1))
      rate = std::max(rate, (p1 - p0).norm() / h);
  }
  out.step = rate > 0 ? 1.0 / rate : 0.0;
  if (o.samples_per_side <= 0)
    out.samples_per_side = std::clamp(int(std::ceil(max_edge * keep / kOffsetSpacing)), 2, kOffsetMaxSide);
  return out;
}

// Face f as camera `cam` may see it: its vertices in front and in the
// image, its front towards `centre` within min_cosine; `p` its projection.
// A superset of the views select_views keeps (no occlusion test).
bool may_use(const TriangleMesh& mesh, const std::vector<Vec3>& normals, const PinholeCamera& cam,
             const Vec3& centre, std::size_t f, double min_cosine, Vec2 p[3]) {
  const Face& face = mesh.faces[f];
  const Vec3 centroid = mesh.face_centroid(f);
  const Vec3 to = centre - centroid;
  const double d = to.norm();
  if (!(d > 0) || normals[f].dot(to) < min_cosine * d || !(normals[f].dot(to) > 0)) return false;
  for (int c = 0; c < 3; ++c)
    if (!cam.project(mesh.vertices[face[c]], &p[c]) || !cam.in_image(p[c])) return false;
  return true;
}

// The least distance (pixels) between rows of a lattice of r subdivisions
// per side on the projected triangle p: its least height over r.
double row_spacing(const Vec2 p[3], double r) {
  const double max_edge = std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
  return max_edge > 0 ? 2.0 * projected_area(p[0], p[1], p[2]) / max_edge / r : 0.0;
}

// PriViewSelection::reductions. A camera's photo can be decoded k times
// smaller when every face that may use it has its lattice rows at least k
// pixels apart there: the reduced image then still resolves everything
// the lattice samples (its Nyquist limit). The spacing of a face in a view
// is bounded below with the face's largest possible r and contraction
// (over every view that may see it) and above with the least; a first
// pass on the upper bound settles most views at 1 after a few faces.
std::vector<int> view_reductions(const Scene& scene, const PriOptions& o, const std::vector<std::size_t>& image_views,
                                 const std::vector<PinholeCamera>& cams, const std::vector<Vec3>& centres,
                                 const std::vector<Vec3>& normals) {
  std::vector<int> out(cams.size(), 1);
  if (o.max_image_reduction <= 1) return out;
  std::vector<std::size_t> candidates;  // views with a JPEG file
  for (std::size_t i = 0; i < cams.size(); ++i) {
    const View& v = scene.views[image_views[i]];
    if (!v.pixels && is_jpeg_file(v.image_path)) candidates.push_back(i);
  }
  if (candidates.empty()) return out;
  const TriangleMesh& mesh = scene.mesh;
  const double min_cosine = std::cos(o.max_incidence_angle * M_PI / 180.0);
  const std::size_t F = mesh.num_faces();
  const bool offset = o.measure == Measure::Offset;
  const int max_side = offset ? kOffsetMaxSide : 32;
  // The lattice's r from the largest projected edge, as select_views sets it.
  const auto side = [&](double max_edge, double keep) {
    if (o.samples_per_side > 0) return double(o.samples_per_side);
    return double(std::clamp(int(std::ceil(offset ? max_edge * keep / kOffsetSpacing : max_edge)), 2, max_side));
  };
  const auto longest = [](const Vec2 p[3]) {
    return std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
  };
  // Pass 1, upper bound: r from this view's edges only, no contraction.
  std::vector<char> open(cams.size(), 0);
  tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t j) {
    const std::size_t i = candidates[j];
    Vec2 p[3];
    for (std::size_t f = 0; f < F; ++f)
      if (may_use(mesh, normals, cams[i], centres[i], f, min_cosine, p) &&
          row_spacing(p, side(longest(p), 1.0 - (o.edge_margin > 0 ? kMaxShrink : 0.0))) < 2.0)
        return;
    open[i] = 1;
  });
  std::vector<std::size_t> left;
  for (std::size_t i : candidates)
    if (open[i]) left.push_back(i);
  if (left.empty()) return out;
  // Pass 2, lower bound: per face, the largest r and contraction over every
  // view that may see it.
  std::vector<float> face_side(F), face_keep(F);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, F), [&](const auto& r) {
    for (std::size_t f = r.begin(); f < r.end(); ++f) {
      double max_edge = 0, shrink = 0;
      Vec2 p[3];
      for (std::size_t i = 0; i < cams.size(); ++i) {
        if (!may_use(mesh, normals, cams[i], centres[i], f, min_cosine, p)) continue;
        const double edge = longest(p);
        max_edge = std::max(max_edge, edge);
        const double inner = edge > 0 ? 2.0 * projected_area(p[0], p[1], p[2]) / (3.0 * edge) : 0.0;
        if (o.edge_margin > 0) shrink = std::max(shrink, inner > 0 ? o.edge_margin / inner : 1.0);
      }
      face_keep[f] = float(1.0 - std::min(shrink, kMaxShrink));
      face_side[f] = float(side(max_edge, 1.0));
    }
  });
  tbb::parallel_for(std::size_t(0), left.size(), [&](std::size_t j) {
    const std::size_t i = left[j];
    double least = std::numeric_limits<double>::infinity();
    Vec2 p[3];
    for (std::size_t f = 0; f < F && least >= 2.0; ++f)
      if (may_use(mesh, normals, cams[i], centres[i], f, min_cosine, p))
        least = std::min(least, double(face_keep[f]) * row_spacing(p, double(face_side[f])));
    int k = 1;
    while (2 * k <= o.max_image_reduction && 2 * k <= least) k *= 2;
    out[i] = k;
  });
  return out;
}

}  // namespace

double ncc_error(const float* a, const float* b, std::size_t n, double min_variance) {
  const PatchStats sa = patch_stats(a, n, min_variance), sb = patch_stats(b, n, min_variance);
  if (sa.textureless || sb.textureless) return -1.0;
  return ncc_from_stats(a, sa, b, sb, n);
}

// Accumulator layout (pair_accumulator_size(n) = n + 4 doubles):
// [0, n) the running mean patch (SSD) or sum_a z_a (NCC); [n] the sum of
// squared deviations from the running mean (SSD) or sum_a |z_a|^2 (NCC);
// [n + 1] patches added; [n + 2] textured patches (NCC); [n + 3] the sum of
// the patches' standard deviations.
std::size_t pair_accumulator_size(std::size_t n) { return n + 4; }

namespace {

// SSD's update of a face's accumulator by one patch: the patch's variance
// (its texture) and Welford's step (the deviations' sum grows by
// (x - old mean)(x - new mean), centred on the running mean patch: no
// cancellation), every sum in sum4's four chains.
double ssd_update(double* acc, const float* patch, std::size_t n, double count, double min_variance) {
  const PatchStats st = patch_stats<true>(patch, n, min_variance);
  acc[n] += sum4(n, [&](std::size_t k) {
    const double x = patch[k], d = x - acc[k];
    acc[k] += d / count;
    return d * (x - acc[k]);
  });
  return st.variance;
}

#ifdef MESHNBV_X86_SIMD
// ssd_update with sum4's chains as the lanes of one vector (element k in
// lane k mod 4, the tail's elements added to lanes 0, 1, 2 in turn, the
// lanes added as (s0 + s1) + (s2 + s3)): the same bits.
__attribute__((target("avx2"))) double ssd_update_avx2(double* acc, const float* patch, std::size_t n,
                                                       double count) {
  const std::size_t body = n & ~std::size_t(3);
  alignas(32) double lanes[4];
  auto finish = [&](auto tail) {  // lanes holds the vector's partial sums
    for (std::size_t k = body; k < n; ++k) lanes[k - body] += tail(k);
    return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
  };
  __m256d sum = _mm256_setzero_pd();
  for (std::size_t k = 0; k < body; k += 4) sum = _mm256_add_pd(sum, _mm256_cvtps_pd(_mm_loadu_ps(patch + k)));
  _mm256_store_pd(lanes, sum);
  const double mean = finish([&](std::size_t k) { return double(patch[k]); }) / double(n);
  const __m256d mean4 = _mm256_set1_pd(mean), count4 = _mm256_set1_pd(count);
  __m256d ss = _mm256_setzero_pd(), dev = _mm256_setzero_pd();
  for (std::size_t k = 0; k < body; k += 4) {
    const __m256d x = _mm256_cvtps_pd(_mm_loadu_ps(patch + k));
    const __m256d c = _mm256_sub_pd(x, mean4);
    ss = _mm256_add_pd(ss, _mm256_mul_pd(c, c));
    const __m256d old = _mm256_loadu_pd(acc + k), d = _mm256_sub_pd(x, old);
    const __m256d now = _mm256_add_pd(old, _mm256_div_pd(d, count4));
    _mm256_storeu_pd(acc + k, now);
    dev = _mm256_add_pd(dev, _mm256_mul_pd(d, _mm256_sub_pd(x, now)));
  }
  _mm256_store_pd(lanes, ss);
  const double spread = finish([&](std::size_t k) { return (patch[k] - mean) * (patch[k] - mean); });
  _mm256_store_pd(lanes, dev);
  acc[n] += finish([&](std::size_t k) {
    const double x = patch[k], d = x - acc[k];
    acc[k] += d / count;
    return d * (x - acc[k]);
  });
  return spread / double(n);
}
#endif

}  // namespace

void pair_accumulate(double* acc, const float* patch, std::size_t n, Measure measure, double min_variance) {
  const double count = acc[n + 1] + 1.0;
  acc[n + 1] = count;
  if (measure == Measure::SSD) {
    double variance;
#ifdef MESHNBV_X86_SIMD
    if (simd_level() == SimdLevel::avx2 && n > 0) variance = ssd_update_avx2(acc, patch, n, count);
    else
#endif
      variance = ssd_update(acc, patch, n, count, min_variance);
    acc[n + 3] += std::sqrt(variance);
    return;
  }
  const PatchStats st = patch_stats(patch, n, min_variance);
  acc[n + 3] += std::sqrt(st.variance);
  if (st.textureless) return;
  acc[n + 2] += 1.0;
  acc[n] += sum1(n, [&](std::size_t k) {  // |z|^2 (1 up to rounding)
    const double z = (double(patch[k]) - st.mean) * st.inv_norm;
    acc[k] += z;
    return z * z;
  });
}

PairSum pair_accumulated_sum(const double* acc, std::size_t n, Measure measure) {
  PairSum out;
  out.patches = std::size_t(acc[n + 1]);
  if (out.patches > 0) out.texture = acc[n + 3] / double(out.patches);
  if (n == 0) return out;
  if (measure == Measure::SSD) {
    // sum_{a<b} |x_a - x_b|^2 / n = m sum_a |x_a - mu|^2 / n.
    if (out.patches < 2) return out;
    out.pairs = out.patches * (out.patches - 1) / 2;
    out.sum = double(out.patches) * acc[n] / double(n);
    return out;
  }
  // NCC: (1 - rho) / 2 summed over the textured pairs.
  const std::size_t textured = std::size_t(acc[n + 2]);
  if (textured < 2) return out;
  const double total = sum1(n, [&](std::size_t k) { return acc[k] * acc[k]; });
  out.pairs = textured * (textured - 1) / 2;
  const double rho_sum = (total - acc[n]) / 2.0;
  out.sum = (double(out.pairs) - rho_sum) / 2.0;
  return out;
}

double pair_error_sum(const std::vector<const float*>& patches, std::size_t n, Measure measure,
                      double min_variance, std::size_t* pairs, std::vector<double>* scratch) {
  std::vector<double>& acc = *scratch;
  acc.assign(pair_accumulator_size(n), 0.0);
  for (const float* p : patches) pair_accumulate(acc.data(), p, n, measure, min_variance);
  const PairSum s = pair_accumulated_sum(acc.data(), n, measure);
  *pairs = s.pairs;
  return s.sum;
}

namespace {

// Whether any point of `box` may project inside the camera's image, in
// front of it: false only when, for a camera without lens distortion, the
// box lies wholly behind it, or the projections of its corners (in front)
// all lie beyond one image edge (with a pixel of margin) -- the projection
// of a box in front of a pinhole camera is the convex hull of its corners'.
// Culls the views of a tile; a culled view sees none of its vertices.
bool may_see_box(const PinholeCamera& c, const BoundingBox& box) {
  if (box.empty() || c.has_distortion()) return true;
  int behind = 0, left = 0, right = 0, above = 0, below = 0;
  for (const Vec3& corner : box.corners()) {
    const Vec3 x = c.R * corner + c.t;
    if (!(x.z() > 0)) {
      ++behind;
      continue;
    }
    const double u = c.fx * x.x() / x.z() + c.skew * x.y() / x.z() + c.cx, v = c.fy * x.y() / x.z() + c.cy;
    left += u < -1.0;
    right += u > c.width;
    above += v < -1.0;
    below += v > c.height;
  }
  if (behind == 8) return false;
  if (behind > 0) return true;
  return !(left == 8 || right == 8 || above == 8 || below == 8);
}

}  // namespace

PriViewSelection select_pri_views(const Scene& scene, const PriOptions& options,
                                  const ProgressCallback& progress,
                                  const std::vector<std::uint32_t>& faces, const RayCaster* caster,
                                  bool views_only) {
  options.check();
  const TriangleMesh& mesh = scene.mesh;
  mesh.validate(scene.mesh_path);
  if (mesh.empty()) throw Error("the mesh has no faces: nothing to compute PRI on");
  PriViewSelection s;
  for (std::size_t i = 0; i < scene.views.size(); ++i)
    if (scene.views[i].has_image() && scene.views[i].used) s.image_views.push_back(i);
  if (s.image_views.size() < 2)
    throw Error("PRI needs at least 2 views with images; the scene has " +
                std::to_string(s.image_views.size()));
  std::vector<Vec3> centres;
  for (std::size_t i : s.image_views) {
    scene.views[i].camera.check("view '" + scene.views[i].label + "'");
    s.cameras.push_back(scene.views[i].camera);
    s.view_keys.push_back(pri_view_key(scene, i));
    centres.push_back(s.cameras.back().center());
  }
  s.options_key = pri_options_key(options);
  const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  const std::vector<Vec3> normals = mesh.face_normals();
  arena.execute(
      [&] { s.reductions = view_reductions(scene, options, s.image_views, s.cameras, centres, normals); });
  if (views_only) return s;
  const std::size_t F = mesh.num_faces();
  for (std::size_t j = 0; j < faces.size(); ++j)
    if (faces[j] >= F || (j > 0 && faces[j] <= faces[j - 1]))
      throw Error("the faces to select views for must be ascending ids below " + std::to_string(F));
  s.face_ids = faces;
  const std::size_t n = faces.empty() ? F : faces.size();
  s.faces.resize(n);
  arena.execute([&] {
    std::unique_ptr<RayCaster> own;
    if (!caster) own = std::make_unique<RayCaster>(mesh);
    const RayCaster& rc = caster ? *caster : *own;
    VertexVisibility vis;
    std::vector<int> usable;  // a tile: the cameras that may see it
    if (faces.empty()) {
      vis = VertexVisibility(mesh, rc, s.cameras, options.visibility, progress);
    } else {
      std::vector<std::uint32_t> vertices;
      vertices.reserve(3 * faces.size());
      for (std::uint32_t f : faces)
        for (int k = 0; k < 3; ++k) vertices.push_back(std::uint32_t(mesh.faces[f][k]));
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      BoundingBox box;
      for (std::uint32_t v : vertices) box.extend(mesh.vertices[v]);
      std::vector<PinholeCamera> cams;
      for (std::size_t i = 0; i < s.cameras.size(); ++i)
        if (may_see_box(s.cameras[i], box)) {
          usable.push_back(int(i));
          cams.push_back(s.cameras[i]);
        }
      vis = VertexVisibility(mesh, rc, cams, options.visibility, progress, vertices);
    }
    const double abs_eps = options.visibility.absolute_eps_of_diagonal * mesh.bounding_box().diagonal();
    // Chunks of faces in parallel; progress and cancellation between chunks.
    constexpr std::size_t kChunk = 16384;
    for (std::size_t begin = 0; begin < n; begin += kChunk) {
      const std::size_t end = std::min(n, begin + kChunk);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end), [&](const auto& r) {
        for (std::size_t j = r.begin(); j < r.end(); ++j)
          s.faces[j] = select_views(mesh, normals, vis, rc, s.cameras, centres, s.face_id(j), options, abs_eps,
                                    faces.empty() ? nullptr : &usable);
      });
      report_progress(progress, double(end) / double(n), "view selection");
    }
  });
  return s;
}

namespace {

// 64-bit keys: splitmix64's finaliser over a running combination.
std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
std::uint64_t combine(std::uint64_t h, std::uint64_t v) { return mix64(h ^ mix64(v)); }

// What a face's value takes from view v: its key, and its photo's
// reduction when reduced (a whole photo leaves the key as it was).
std::uint64_t view_evidence(const PriViewSelection& s, std::size_t v) {
  const int r = s.reductions.empty() ? 1 : s.reductions[v];
  return r > 1 ? combine(s.view_keys[v], std::uint64_t(r)) : s.view_keys[v];
}
std::uint64_t combine(std::uint64_t h, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return combine(h, bits);
}
std::uint64_t combine(std::uint64_t h, const std::string& text) {
  std::uint64_t fnv = 0xcbf29ce484222325ull;  // FNV-1a
  for (unsigned char c : text) fnv = (fnv ^ c) * 0x100000001b3ull;
  return combine(combine(h, std::uint64_t(text.size())), fnv);
}

}  // namespace

std::uint64_t pri_view_key(const Scene& scene, std::size_t view) {
  const View& v = scene.views.at(view);
  const PinholeCamera& c = v.camera;
  std::uint64_t h = 0x6d6573686e6276ull;  // "meshnbv"
  for (double x : {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2, c.k3, c.k4, c.k5, c.k6, c.p1, c.p2, c.skew}) h = combine(h, x);
  h = combine(h, std::uint64_t(c.width) << 32 | std::uint32_t(c.height));
  h = combine(h, std::uint64_t(c.lens));
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) h = combine(h, c.R(r, k));
    h = combine(h, c.t[r]);
  }
  if (v.pixels) {
    const Image& im = *v.pixels;
    h = combine(h, std::uint64_t(im.width()) << 40 ^ std::uint64_t(im.height()) << 8 ^ std::uint64_t(im.channels()));
    if (im.bits() != 8) h = combine(h, std::uint64_t(im.bits()));
    const std::uint8_t* d = im.data();
    std::size_t k = 0;
    for (; k + 8 <= im.bytes(); k += 8) {
      std::uint64_t w;
      std::memcpy(&w, d + k, 8);
      h = combine(h, w);
    }
    for (; k < im.bytes(); ++k) h = combine(h, std::uint64_t(d[k]));
    return h;
  }
  h = combine(h, v.image_path);
  if (v.orientation != ImageOrientation::stored) h = combine(h, std::uint64_t(v.orientation));
  std::error_code ec;
  const auto size = std::filesystem::file_size(v.image_path, ec);
  if (!ec) h = combine(h, std::uint64_t(size));
  const auto time = std::filesystem::last_write_time(v.image_path, ec);
  if (!ec) h = combine(h, std::uint64_t(time.time_since_epoch().count()));
  return h;
}

std::vector<std::uint64_t> pri_view_keys(const Scene& scene) {
  std::vector<std::uint64_t> keys;
  for (std::size_t i = 0; i < scene.views.size(); ++i)
    if (scene.views[i].has_image() && scene.views[i].used) keys.push_back(pri_view_key(scene, i));
  return keys;
}

std::uint64_t pri_options_key(const PriOptions& options) {
  std::uint64_t h = 0x7072696f707473ull;  // "priopts"
  for (const auto& spec : pri_option_table()) {
    if (spec.name == "threads") continue;  // does not change a value
    h = combine(combine(h, spec.name), option_value_text(spec.get(options)));
  }
  h = combine(h, options.visibility.relative_eps);
  h = combine(h, options.visibility.absolute_eps_of_diagonal);
  return h;
}

std::vector<std::vector<std::uint32_t>> pri_tiles(const TriangleMesh& mesh, std::size_t count,
                                                  const std::vector<std::uint32_t>& faces) {
  std::vector<std::uint32_t> ids = faces;
  if (faces.empty()) {
    ids.resize(mesh.num_faces());
    std::iota(ids.begin(), ids.end(), 0u);
  }
  std::vector<std::vector<std::uint32_t>> tiles;
  if (ids.empty() || count == 0) return tiles;
  BoundingBox box;
  for (std::uint32_t f : ids) box.extend(mesh.face_centroid(f));
  // One scale on every axis (the largest extent), so that a run is compact
  // in space, not in the box's normalised coordinates.
  const Vec3 extent = Vec3::Constant(std::max(box.extent().maxCoeff(), 1e-300));
  // 21 bits per axis, interleaved.
  auto spread = [](std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(ids.size());
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const Vec3 u = (mesh.face_centroid(ids[j]) - box.min).cwiseQuotient(extent);
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k)
      code |= spread(std::uint64_t(std::clamp(u[k], 0.0, 1.0) * 2097151.0)) << k;
    keyed[j] = {code, ids[j]};
  }
  std::sort(keyed.begin(), keyed.end());
  count = std::min(count, keyed.size());
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t begin = keyed.size() * t / count, end = keyed.size() * (t + 1) / count;
    std::vector<std::uint32_t> tile;
    for (std::size_t j = begin; j < end; ++j) tile.push_back(keyed[j].second);
    std::sort(tile.begin(), tile.end());
    tiles.push_back(std::move(tile));
  }
  return tiles;
}

namespace {

// Samples of face f's lattice: (r + 1)(r + 2) / 2 points.
std::size_t lattice_points(int r) { return std::size_t(r + 1) * (r + 2) / 2; }

// What every phase of compute_pri reads.
struct PriInputs {
  const Scene& scene;
  const PriViewSelection& selection;
  const PriOptions& options;
  int channels;  // 3 with options.color, else 1 (luminance)
  // offset: the hypotheses, in pixels of disparity of the fastest view
  // (hypothesis_offsets); empty for the other measures.
  std::vector<double> hypotheses_px;
};

// Lattices per (face, view): one per offset hypothesis, else one.
int hypotheses(const PriOptions& o) { return o.measure == Measure::Offset ? 2 * o.offset_steps + 1 : 1; }

// The offset sweep's hypotheses j = -steps..steps, in pixels of the fastest
// view: offset_range (|j| / steps)^1.5 with the sign of j -- finer near
// zero, where most faces are, coarser towards the range.
std::vector<double> hypothesis_offsets(const PriOptions& o) {
  std::vector<double> out;
  if (o.measure != Measure::Offset) return out;
  for (int j = -o.offset_steps; j <= o.offset_steps; ++j) {
    const double t = std::pow(double(std::abs(j)) / double(o.offset_steps), kOffsetSpacingPower);
    out.push_back(j < 0 ? -o.offset_range * t : o.offset_range * t);
  }
  return out;
}

// Floats of one lattice of face fv, and of its (face, view) slot.
std::size_t lattice_floats(const PriInputs& in, const PriFaceViews& fv) {
  return lattice_points(fv.samples_per_side) * std::size_t(in.channels);
}
std::size_t slot_floats(const PriInputs& in, const PriFaceViews& fv) {
  return lattice_floats(in, fv) * std::size_t(hypotheses(in.options));
}

// The offset measure (its sweeps compare every view with the reference, so
// the samples are kept): consecutive faces [begin, end) and the samples of
// each (face, view); the slots of face f are consecutive, one per view of
// fv[f].views.
struct SampleBlock {
  std::size_t begin = 0, end = 0;
  std::vector<std::size_t> offset;  // first float of face begin + j
  std::unique_ptr<float[]> samples;
  // Per view, the faces of the block that it sees and the slot of each.
  std::vector<std::vector<std::pair<std::size_t, int>>> by_view;

  float* slot(std::size_t f, std::size_t k, std::size_t floats_per_view) const {
    return &samples[offset[f - begin] + k * floats_per_view];
  }
};

// Faces from `begin` in a block whose sample storage stays under ~1 GB;
// each block visits every view once (one image decoded and converted at a
// time).
SampleBlock plan_block(const PriInputs& in, std::size_t begin) {
  const std::vector<PriFaceViews>& fv = in.selection.faces;
  const std::size_t budget = std::size_t(256) << 20;  // floats
  SampleBlock block;
  block.begin = block.end = begin;
  std::size_t floats = 0;
  while (block.end < fv.size()) {
    const std::size_t need = slot_floats(in, fv[block.end]) * fv[block.end].views.size();
    if (floats + need > budget && block.end > begin) break;
    block.offset.push_back(floats);
    floats += need;
    ++block.end;
  }
  // Every slot is written by its view before it is read: no zero fill.
  block.samples.reset(new float[floats]);
  block.by_view.resize(in.selection.cameras.size());
  for (std::size_t f = block.begin; f < block.end; ++f)
    for (std::size_t k = 0; k < fv[f].views.size(); ++k)
      block.by_view[std::size_t(fv[f].views[k])].emplace_back(f, int(k));
  return block;
}

// One view's image plane and projection, as the lattice sampling uses them.
struct ViewSampler {
  const FloatImage& plane;
  const PinholeCamera& cam;
  int channels;
  // Without distortion the projection of a lattice point is the same
  // barycentric mix of the vertices' homogeneous projections: three matrix
  // products per (face, view) instead of one per sample.
  bool linear;
  Mat3 KR;
  Vec3 Kt;
  // The plane is the photo decoded `reduction` times smaller: a full-size
  // pixel position x is x' = (x + 0.5) / reduction - 0.5 on it (a reduced
  // pixel is centred on the block it averages).
  int reduction = 1;
};

// Camera cam's sampler on `plane`, decoded `reduction` times smaller.
ViewSampler make_sampler(const FloatImage& plane, const PinholeCamera& cam, int channels, int reduction) {
  ViewSampler v{plane, cam, channels, !cam.has_distortion(), cam.K() * cam.R, cam.K() * cam.t, reduction};
  if (reduction > 1) {
    // The pixel map x' = x / k + (0.5 / k - 0.5) folded into the homogeneous
    // projection (rows 0 and 1 scaled, plus the offset times row 2).
    const double inv = 1.0 / reduction, shift = 0.5 * inv - 0.5;
    for (int r = 0; r < 2; ++r) {
      v.KR.row(r) = inv * v.KR.row(r) + shift * v.KR.row(2);
      v.Kt[r] = inv * v.Kt[r] + shift * v.Kt[2];
    }
  }
  return v;
}

// Samples the lattice of triangle (w0, w1, w2), rs subdivisions per side,
// into `out`; false when a sample is behind the camera or off the image.
inline bool sample_lattice(const ViewSampler& view, const Vec3& w0, const Vec3& w1, const Vec3& w2,
                           int rs, float* out) {
  const FloatImage& plane = view.plane;
  const int channels = view.channels;
  const bool linear = view.linear;
  const Vec3 h0 = view.KR * w0 + view.Kt, h1 = view.KR * w1 + view.Kt, h2 = view.KR * w2 + view.Kt;
  if (linear && channels == 1) {
    // Lattice point (a, b, c) with a + b + c = rs: along a row of constant
    // a, the homogeneous projection moves by h1 - h2.
    // The points of each row are stepped in sequence (the same sums
    // whatever the kernel) into a buffer of the lattice's points in order,
    // sampled together (sample_gray_homogeneous) each time it fills.
    const Vec3 step = h1 - h2;
    constexpr int kChunk = 64;
    double hx[kChunk], hy[kChunk], hz[kChunk];
    int m = 0;
    for (int a = 0; a <= rs; ++a) {
      Vec3 h = double(a) * h0 + double(rs - a) * h2;
      for (int b = 0; b <= rs - a; ++b, h += step) {
        hx[m] = h.x(), hy[m] = h.y(), hz[m] = h.z();
        if (++m == kChunk) {
          if (!sample_gray_homogeneous(plane, hx, hy, hz, std::size_t(m), out)) return false;
          out += m;
          m = 0;
        }
      }
    }
    if (m > 0 && !sample_gray_homogeneous(plane, hx, hy, hz, std::size_t(m), out)) return false;
    return true;
  }
  std::size_t s = 0;
  for (int a = 0; a <= rs; ++a)
    for (int b = 0; b <= rs - a; ++b, ++s) {
      const int c = rs - a - b;
      float* o = out + s * channels;
      bool ok;
      if (linear) {
        const Vec3 h = double(a) * h0 + double(b) * h1 + double(c) * h2;
        ok = h.z() > 0 && plane.sample(h.x() / h.z(), h.y() / h.z(), o);
      } else {
        const Vec3 X = (a * w0 + b * w1 + c * w2) / double(rs);
        Vec2 px;
        ok = view.cam.project(X, &px);
        if (ok && view.reduction > 1) px = (px.array() + 0.5) / double(view.reduction) - 0.5;
        ok = ok && plane.sample(px.x(), px.y(), o);
      }
      if (!ok) return false;
    }
  return true;
}

// Samples face f's lattice in one view into `slot` (one lattice per
// hypothesis: `hypotheses` offsets of fv.step along the normal, centred on
// zero); NaN in slot[0] when the view is unusable there (a sample behind
// the camera or off the image).
inline void sample_face(const TriangleMesh& mesh, std::size_t f, const PriFaceViews& fv,
                        const ViewSampler& view, const std::vector<double>& hypotheses_px, float* slot) {
  const int rs = fv.samples_per_side;
  const Face& face = mesh.faces[f];
  const Vec3 &v0 = mesh.vertices[face[0]], &v1 = mesh.vertices[face[1]], &v2 = mesh.vertices[face[2]];
  // The lattice, contracted towards the centroid by the face's edge-margin
  // factor (the same 3-D points in every view).
  const double keep = 1.0 - fv.shrink;
  const Vec3 g = (v0 + v1 + v2) / 3.0;
  const Vec3 w0 = g + keep * (v0 - g), w1 = g + keep * (v1 - g), w2 = g + keep * (v2 - g);
  bool ok = true;
  if (hypotheses_px.empty()) {
    ok = sample_lattice(view, w0, w1, w2, rs, slot);
  } else {
    const Vec3 n = (v1 - v0).cross(v2 - v0).normalized();
    const std::size_t floats = lattice_points(rs) * std::size_t(view.channels);
    for (std::size_t k = 0; k < hypotheses_px.size() && ok; ++k) {
      const Vec3 d = hypotheses_px[k] * fv.step * n;
      ok = sample_lattice(view, w0 + d, w1 + d, w2 + d, rs, slot + k * floats);
    }
  }
  if (!ok) slot[0] = std::numeric_limits<float>::quiet_NaN();  // view unusable here
}

// One view's photo made ready for sampling, by a task of its own: decoded
// (through the scene's image cache) and converted to the sampling plane.
struct PreparedView {
  std::size_t view = 0;
  FloatImage plane;
  int reduction = 1;  // the plane's (Image::reduction)
  std::exception_ptr error;  // the decoding's, thrown when the view's turn comes
  tbb::task_group work;
};

void prepare_view(const PriInputs& in, PreparedView* p) {
  try {
    const int reduction = in.selection.reductions.empty() ? 1 : in.selection.reductions[p->view];
    const auto image = in.scene.image(in.selection.image_views[p->view], reduction);
    p->reduction = image->reduction();
    p->plane = in.options.color ? FloatImage::rgb_of(*image) : FloatImage::luminance_of(*image);
  } catch (...) {
    p->error = std::current_exception();
  }
}

// The photos of a block's views in order, each prepared ahead of its turn:
// at most `ahead` at a time beyond the one being sampled (the memory bound),
// decoding and conversion in parallel with the sampling of earlier views.
class ViewQueue {
 public:
  // `order`: the views in the order they are taken, only those the block
  // needs (no other is decoded).
  ViewQueue(const PriInputs& in, std::vector<std::size_t> order, std::size_t ahead)
      : in_(in), ahead_(ahead), order_(std::move(order)) {
    launch();
  }
  ~ViewQueue() {  // on an exception too: no task may outlive what it writes
    for (auto& p : queue_) p->work.wait();
  }
  // The next view's plane (throws that view's decoding error).
  std::unique_ptr<PreparedView> next() {
    std::unique_ptr<PreparedView> p = std::move(queue_.front());
    queue_.pop_front();
    p->work.wait();
    launch();
    if (p->error) std::rethrow_exception(p->error);
    return p;
  }

 private:
  void launch() {
    while (launched_ < order_.size() && queue_.size() < ahead_) {
      auto p = std::make_unique<PreparedView>();
      p->view = order_[launched_++];
      PreparedView* raw = p.get();
      const PriInputs* in = &in_;
      raw->work.run([in, raw] { prepare_view(*in, raw); });
      queue_.push_back(std::move(p));
    }
  }
  const PriInputs& in_;
  const std::size_t ahead_;
  std::vector<std::size_t> order_;
  std::size_t launched_ = 0;
  std::deque<std::unique_ptr<PreparedView>> queue_;
};

// Camera i samples every face of the block that it sees, on `plane`.
void sample_view(const PriInputs& in, const SampleBlock& block, std::size_t i, const FloatImage& plane,
                 int reduction) {
  const std::vector<std::pair<std::size_t, int>>& faces = block.by_view[i];
  const std::vector<PriFaceViews>& fv = in.selection.faces;
  const ViewSampler view = make_sampler(plane, in.selection.cameras[i], in.channels, reduction);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size()), [&](const auto& r) {
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const auto [f, k] = faces[j];
      sample_face(in.scene.mesh, in.selection.face_id(f), fv[f], view, in.hypotheses_px,
                  block.slot(f, std::size_t(k), slot_floats(in, fv[f])));
    }
  });
}

struct PairErrors {
  double sum = 0;
  std::size_t pairs = 0;  // pairs that count (NCC skips textureless ones)
  double curvature = 0;   // offset: cost curvature at the minimum (per pixel^2)
  double best_cost = 0;   // offset: the least cost
  bool steady = false;    // offset: least cost at an end, reached by a steady fall (kSteadyRise)
};

// The offset measure on a face's patches (each one lattice of n floats per
// hypothesis of x_px, the hypotheses in pixels; `ref` the reference
// view's): for every hypothesis the mean NCC error of the other views
// against the reference, then the hypothesis of least error, refined by a
// parabola through it and its neighbours. Sets e.sum to the offset in
// pixels of the fastest view (signed), e.curvature and e.best_cost at that
// minimum (curvature 0 at an end of the sweep), e.steady where that end is
// reached by a steady fall of the cost, and e.pairs to the views
// compared at zero offset; e.pairs = 0 when the reference or every other
// view is textureless at zero offset.
PairErrors offset_errors(const std::vector<const float*>& patches, std::size_t ref, std::size_t n,
                         const std::vector<double>& x_px, const PriOptions& o, std::vector<double>* costs) {
  PairErrors e;
  const int hypotheses = int(x_px.size());
  const int half = hypotheses / 2;
  costs->assign(std::size_t(hypotheses), std::numeric_limits<double>::infinity());
  for (int k = 0; k < hypotheses; ++k) {
    const std::size_t at = std::size_t(k) * n;
    const PatchStats sr = patch_stats(patches[ref] + at, n, o.textureless_variance);
    if (sr.textureless) continue;
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      if (i == ref) continue;
      const PatchStats si = patch_stats(patches[i] + at, n, o.textureless_variance);
      if (si.textureless) continue;
      sum += ncc_from_stats(patches[ref] + at, sr, patches[i] + at, si, n);
      ++count;
    }
    if (count > 0) (*costs)[std::size_t(k)] = sum / double(count);
    if (k == half) e.pairs = count;
  }
  if (e.pairs == 0) return e;
  const std::vector<double>& c = *costs;
  const int best = int(std::min_element(c.begin(), c.end()) - c.begin());
  double x = x_px[std::size_t(best)];
  if (best > 0 && best + 1 < hypotheses && std::isfinite(c[best - 1]) && std::isfinite(c[best + 1])) {
    // The vertex of the parabola through the best hypothesis and its two
    // neighbours (unequal spacing), kept between those neighbours.
    const double x0 = x_px[std::size_t(best - 1)], x2 = x_px[std::size_t(best + 1)];
    const double d0 = (c[best - 1] - c[best]) / (x0 - x), d2 = (c[best + 1] - c[best]) / (x2 - x);
    const double a = (d2 - d0) / (x2 - x0);  // curvature / 2
    if (a > 0) x = std::clamp(0.5 * (x + x2 - d2 / a), x0, x2);
    e.curvature = std::max(a, 0.0);
  }
  if (best == 0 || best + 1 == hypotheses) {
    const int step = best == 0 ? -1 : 1;
    const double tolerance = kSteadyRise * (c[half] - c[best]);
    e.steady = true;
    for (int k = half; k != best; k += step)
      if (!(c[k + step] <= c[k] + tolerance)) e.steady = false;  // also false on a missing cost
  }
  e.best_cost = c[best];
  e.sum = x;  // pixels of the fastest view
  return e;
}

// Mean standard deviation of the patches (n floats each, at `at`).
float texture_of(const std::vector<const float*>& patches, std::size_t at, std::size_t n) {
  double sum = 0;
  for (const float* p : patches) {
    double mean = 0, ss = 0;
    for (std::size_t k = 0; k < n; ++k) mean += p[at + k];
    mean /= double(n);
    for (std::size_t k = 0; k < n; ++k) ss += (p[at + k] - mean) * (p[at + k] - mean);
    sum += std::sqrt(ss / double(n));
  }
  return float(sum / double(patches.size()));
}

// Face f's evidence key (options and its views' keys), usable views and
// lattice samples.
void set_face_evidence(const PriInputs& in, std::size_t f, std::size_t usable, PriResult* result) {
  const PriFaceViews& fv = in.selection.faces[f];
  std::uint64_t key = in.selection.options_key;
  for (int v : fv.views) key = combine(key, view_evidence(in.selection, std::size_t(v)));
  result->evidence_key[f] = key;
  result->pri_views[f] = int(usable);
  result->pri_samples[f] = int(lattice_points(fv.samples_per_side));
}

// The offset measure: PRI (signed, before smooth_offsets), views, status,
// evidence and precision of every face of the block from its samples.
// (Positions f of the selection: face in.selection.face_id(f); `result`'s
// arrays are indexed by position.)
void score_block(const PriInputs& in, const SampleBlock& block, PriResult* result) {
  const std::vector<PriFaceViews>& fv = in.selection.faces;
  const int hyps = hypotheses(in.options);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(block.begin, block.end), [&](const auto& r) {
    std::vector<const float*> patches;
    std::vector<double> costs;
    for (std::size_t f = r.begin(); f < r.end(); ++f) {
      const std::size_t n = lattice_floats(in, fv[f]);
      const std::size_t stride = slot_floats(in, fv[f]);
      patches.clear();
      std::size_t ref = 0;
      for (std::size_t k = 0; k < fv[f].views.size(); ++k) {
        const float* slot = block.slot(f, k, stride);
        if (std::isnan(slot[0])) continue;
        if (int(k) == fv[f].reference) ref = patches.size();
        patches.push_back(slot);
      }
      set_face_evidence(in, f, patches.size(), result);
      if (patches.size() < 2) continue;  // unobserved
      result->pri_texture[f] = texture_of(patches, std::size_t(hyps / 2) * n, n);
      const PairErrors e = offset_errors(patches, ref, n, in.hypotheses_px, in.options, &costs);
      result->pri_pairs[f] = int(e.pairs);
      if (e.pairs == 0) {
        result->status[f] = FaceStatus::Textureless;
        continue;
      }
      // Signed here; smooth_offsets() averages and takes the magnitude.
      result->pri[f] = float(e.sum * fv[f].step);
      result->offset_signed[f] = result->pri[f];
      result->offset_pixel[f] = float(fv[f].pixel);
      result->offset_steady[f] = e.steady ? 1.0f : 0.0f;
      // The estimate's precision (inverse variance, up to a common factor)
      // by the Laplace approximation of the sweep: the cost's curvature at
      // its minimum times the comparisons made (views x samples) over the
      // residual noise, the least cost. A minimum at an end of the sweep
      // has no curvature: no weight.
      result->offset_precision[f] = float(e.curvature * double(e.pairs) * double(n) / std::max(e.best_cost, kMinResidualCost));
      result->status[f] = FaceStatus::Observed;
    }
  });
}

// SSD and NCC streamed (pair_accumulate): each face of a block holds only
// its accumulator, which takes the face's patch in each view as that view
// is sampled; no patch is stored, so a block holds ~30x the faces of a
// SampleBlock and the photos are usually decoded once. The views are
// always taken in ascending order, each face's in the order of its view
// list: the sums are bitwise those of pair_error_sum over the face's
// patches, whatever the blocks, tiles, ranks and threads.
struct StreamBlock {
  std::size_t begin = 0, end = 0;
  std::vector<std::size_t> offset;  // first double of face begin + j
  std::unique_ptr<double[]> acc;
  std::vector<std::vector<std::uint32_t>> by_view;  // per view, the faces (f - begin) it sees
};

// Faces from `begin` in a block whose accumulators and view lists stay
// under ~1 GB.
StreamBlock plan_stream_block(const PriInputs& in, std::size_t begin) {
  const std::vector<PriFaceViews>& fv = in.selection.faces;
  const std::size_t budget = std::size_t(1) << 30;  // bytes
  StreamBlock block;
  block.begin = block.end = begin;
  std::size_t doubles = 0, bytes = 0;
  while (block.end < fv.size() && block.end - begin < std::numeric_limits<std::uint32_t>::max()) {
    const std::size_t need = pair_accumulator_size(lattice_floats(in, fv[block.end]));
    const std::size_t more = need * sizeof(double) + fv[block.end].views.size() * sizeof(std::uint32_t) + sizeof(std::size_t);
    if (bytes + more > budget && block.end > begin) break;
    block.offset.push_back(doubles);
    doubles += need;
    bytes += more;
    ++block.end;
  }
  block.acc.reset(new double[doubles]());
  block.by_view.resize(in.selection.cameras.size());
  for (std::size_t f = block.begin; f < block.end; ++f)
    for (int v : fv[f].views) block.by_view[std::size_t(v)].push_back(std::uint32_t(f - block.begin));
  return block;
}

// Camera i samples every face of the block that it sees, on `plane`, into
// the faces' accumulators.
void stream_view(const PriInputs& in, StreamBlock* block, std::size_t i, const FloatImage& plane,
                 int reduction) {
  const std::vector<std::uint32_t>& faces = block->by_view[i];
  const std::vector<PriFaceViews>& fv = in.selection.faces;
  const ViewSampler view = make_sampler(plane, in.selection.cameras[i], in.channels, reduction);
  const Measure measure = in.options.measure;
  const double min_variance = in.options.textureless_variance;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size()), [&](const auto& r) {
    std::vector<float> patch;
    for (std::size_t j = r.begin(); j < r.end(); ++j) {
      const std::size_t f = block->begin + faces[j];
      const std::size_t n = lattice_floats(in, fv[f]);
      patch.resize(n);
      sample_face(in.scene.mesh, in.selection.face_id(f), fv[f], view, in.hypotheses_px, patch.data());
      if (std::isnan(patch[0])) continue;  // view unusable here
      pair_accumulate(&block->acc[block->offset[faces[j]]], patch.data(), n, measure, min_variance);
    }
  });
}

// PRI, views, status and evidence of every face of a streamed block.
void score_stream_block(const PriInputs& in, const StreamBlock& block, PriResult* result) {
  const std::vector<PriFaceViews>& fv = in.selection.faces;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(block.begin, block.end), [&](const auto& r) {
    for (std::size_t f = r.begin(); f < r.end(); ++f) {
      const std::size_t n = lattice_floats(in, fv[f]);
      const PairSum e = pair_accumulated_sum(&block.acc[block.offset[f - block.begin]], n, in.options.measure);
      set_face_evidence(in, f, e.patches, result);
      if (e.patches < 2) continue;  // unobserved
      result->pri_texture[f] = float(e.texture);
      result->pri_pairs[f] = int(e.pairs);
      if (e.pairs == 0) {
        result->status[f] = FaceStatus::Textureless;
        continue;
      }
      result->pri[f] = float(e.sum / double(e.pairs));
      result->status[f] = FaceStatus::Observed;
    }
  });
}

// Faces around each vertex (CSR: faces of vertex v at [start[v], start[v+1])).
struct VertexFaces {
  std::vector<std::size_t> start;
  std::vector<std::uint32_t> faces;
  explicit VertexFaces(const TriangleMesh& mesh) : start(mesh.vertices.size() + 1, 0) {
    for (const Face& face : mesh.faces)
      for (int k = 0; k < 3; ++k) ++start[std::size_t(face[k]) + 1];
    for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    faces.resize(start.back());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) faces[fill[std::size_t(mesh.faces[f][k])]++] = std::uint32_t(f);
  }
};

// The faces connected to f through shared vertices whose centroids lie
// within `radius` of f's (f and the faces around its vertices always), at
// most kMaxSupportFaces, sorted.
constexpr std::size_t kMaxSupportFaces = 512;
void support_faces(const TriangleMesh& mesh, const VertexFaces& vf, std::size_t f, double radius,
                   std::vector<std::uint32_t>* out, std::vector<std::uint32_t>* frontier) {
  out->assign(1, std::uint32_t(f));
  frontier->assign(1, std::uint32_t(f));
  const Vec3 c = mesh.face_centroid(f);
  std::vector<std::uint32_t> next;
  for (bool first = true; !frontier->empty() && out->size() < kMaxSupportFaces; first = false) {
    next.clear();
    for (std::uint32_t g : *frontier)
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = std::size_t(mesh.faces[g][k]);
        for (std::size_t i = vf.start[v]; i < vf.start[v + 1]; ++i) {
          const std::uint32_t h = vf.faces[i];
          if (std::binary_search(out->begin(), out->end(), h)) continue;
          if (!first && (mesh.face_centroid(h) - c).norm() > radius) continue;
          out->insert(std::upper_bound(out->begin(), out->end(), h), h);
          next.push_back(h);
        }
      }
    frontier->swap(next);
  }
}

// The offset measure's support: each observed face's signed offset becomes
// the weighted mean over the observed faces connected to it within 2 sigma
// (sigma = support_radius pixels of the face's reference view, on the
// distance between centroids), each weighted by a Gaussian of that distance
// times its estimate's `precision` (score_block); PRI is its magnitude.
// Faces at an end of the sweep vote for keeping it where `offset_steady`.
void smooth_offsets(const TriangleMesh& mesh, const PriOptions& o, PriResult* result) {
  const std::size_t F = mesh.num_faces();
  const std::vector<float>& signed_offset = result->offset_signed;
  const std::vector<float>& precision = result->offset_precision;
  const VertexFaces vf(mesh);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, F), [&](const auto& r) {
    std::vector<std::uint32_t> near, frontier;
    for (std::size_t f = r.begin(); f < r.end(); ++f) {
      if (result->status[f] != FaceStatus::Observed) continue;
      const double sigma = o.support_radius * double(result->offset_pixel[f]);
      if (!(sigma > 0)) {
        result->pri[f] = std::abs(signed_offset[f]);
        continue;
      }
      support_faces(mesh, vf, f, 2 * sigma, &near, &frontier);
      const Vec3 c = mesh.face_centroid(f);
      double sum = 0, weight = 0, at_end = 0, all = 0;
      for (std::uint32_t g : near) {
        if (result->status[g] != FaceStatus::Observed) continue;
        const double d2 = (mesh.face_centroid(g) - c).squaredNorm();
        const double gauss = std::exp(-d2 / (2 * sigma * sigma));
        const double w = gauss * precision[g];
        sum += w * signed_offset[g];
        weight += w;
        all += gauss;
        if (result->offset_steady[g] > 0) at_end += gauss;  // an end (no curvature), reached steadily
      }
      double value = weight > 0 ? std::abs(sum / weight) : std::abs(signed_offset[f]);
      // Where most of the support has its best offset at an end of the
      // sweep, reached by a steady fall of the cost (the error exceeds the
      // range; a wavering fall is a failed match), such a face keeps that
      // end if its own evidence holds (3 views or more, texture at least
      // kLowTexture): the few neighbours with a minimum cannot vouch for a
      // smaller error. An isolated face at an end, or one on two views or
      // low texture, is a failed match among good ones and is smoothed.
      const bool evidence = result->pri_pairs[f] >= 2 && result->pri_texture[f] >= kLowTexture;
      if (!(precision[f] > 0) && evidence && at_end >= 0.5 * all)
        value = std::max(value, double(std::abs(signed_offset[f])));
      result->pri[f] = float(value);
    }
  });
}

void count_statuses(PriResult* result) {
  for (FaceStatus s : result->status) {
    if (s == FaceStatus::Observed) ++result->observed;
    else if (s == FaceStatus::Unobserved) ++result->unobserved;
    else ++result->textureless;
  }
}

}  // namespace

namespace {

// Every per-face array of `r` sized n, at the "not computed" values.
void init_result(PriResult* r, std::size_t n, const PriOptions& options) {
  r->pri.assign(n, std::numeric_limits<float>::quiet_NaN());
  r->pri_views.assign(n, 0);
  r->status.assign(n, FaceStatus::Unobserved);
  r->pri_pairs.assign(n, 0);
  r->pri_samples.assign(n, 0);
  r->pri_texture.assign(n, std::numeric_limits<float>::quiet_NaN());
  r->evidence_key.assign(n, 0);
  const std::size_t m = options.measure == Measure::Offset ? n : 0;
  r->offset_signed.assign(m, std::numeric_limits<float>::quiet_NaN());
  r->offset_precision.assign(m, 0.0f);
  r->offset_pixel.assign(m, 0.0f);
  r->offset_steady.assign(m, 0.0f);
}

// Face `from` of `a` into face `to` of `b` (every per-face array).
void copy_face(const PriResult& a, std::size_t from, PriResult* b, std::size_t to) {
  b->pri[to] = a.pri[from];
  b->pri_views[to] = a.pri_views[from];
  b->status[to] = a.status[from];
  b->pri_pairs[to] = a.pri_pairs[from];
  b->pri_samples[to] = a.pri_samples[from];
  b->pri_texture[to] = a.pri_texture[from];
  b->evidence_key[to] = a.evidence_key[from];
  if (!b->offset_signed.empty()) {
    b->offset_signed[to] = a.offset_signed[from];
    b->offset_precision[to] = a.offset_precision[from];
    b->offset_pixel[to] = a.offset_pixel[from];
    b->offset_steady[to] = a.offset_steady[from];
  }
}

int thread_count(const PriOptions& options) {
  return options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
}

}  // namespace

PriPart compute_pri_part(const Scene& scene, const PriOptions& options, const PriViewSelection& selection,
                         const ProgressCallback& progress) {
  const PriInputs in{scene, selection, options, options.color ? 3 : 1, hypothesis_offsets(options)};
  const std::size_t n = selection.faces.size();
  const std::size_t views = selection.cameras.size();
  PriPart part;
  part.faces.resize(n);
  for (std::size_t j = 0; j < n; ++j) part.faces[j] = selection.face_id(j);
  PriResult& result = part.values;
  init_result(&result, n, options);
  result.views_used = selection.image_views.size();
  result.views_reduced = std::size_t(std::count_if(selection.reductions.begin(), selection.reductions.end(),
                                                   [](int r) { return r > 1; }));
  result.recomputed = n;
  const std::size_t loads_before = scene.images ? scene.images->loads() : 0;
  tbb::task_arena arena(thread_count(options));
  arena.execute([&] {
    // Photos prepared ahead: as many as threads, at most 4.
    const std::size_t ahead = std::size_t(std::clamp(thread_count(options), 1, 4));
    // Blocks take the views forwards and backwards in turn: a block starts
    // with the photos the one before it ended with, which the image cache
    // still holds (fewer decodes when the photos outgrow the cache; the
    // samples do not depend on the order).
    std::vector<std::size_t> order(views);
    for (std::size_t i = 0; i < views; ++i) order[i] = i;
    const auto progress_at = [&](std::size_t begin, std::size_t end, std::size_t j) {
      const double done = (double(begin) + double(end - begin) * double(j + 1) / double(views)) / double(n);
      report_progress(progress, 0.95 * done, "pri");
    };
    const auto needed = [&](const auto& by_view) {
      std::vector<std::size_t> out;
      for (std::size_t i : order)
        if (!by_view[i].empty()) out.push_back(i);
      return out;
    };
    if (options.measure != Measure::Offset) {
      for (std::size_t begin = 0; begin < n;) {
        StreamBlock block = plan_stream_block(in, begin);
        ViewQueue queue(in, needed(block.by_view), ahead);
        for (std::size_t i = 0; i < views; ++i) {
          if (!block.by_view[i].empty()) {
            const std::unique_ptr<PreparedView> view = queue.next();
            stream_view(in, &block, i, view->plane, view->reduction);
          }
          progress_at(block.begin, block.end, i);
        }
        score_stream_block(in, block, &result);
        begin = block.end;
      }
      return;
    }
    for (std::size_t begin = 0; begin < n; std::reverse(order.begin(), order.end())) {
      const SampleBlock block = plan_block(in, begin);
      ViewQueue queue(in, needed(block.by_view), ahead);
      for (std::size_t j = 0; j < views; ++j) {
        const std::size_t i = order[j];
        if (!block.by_view[i].empty()) {
          const std::unique_ptr<PreparedView> view = queue.next();
          sample_view(in, block, i, view->plane, view->reduction);
        }
        progress_at(block.begin, block.end, j);
      }
      score_block(in, block, &result);
      begin = block.end;
    }
  });
  result.images_decoded = scene.images ? scene.images->loads() - loads_before : 0;
  return part;
}

PriResult assemble_pri(const Scene& scene, const PriOptions& options, const std::vector<PriPart>& parts) {
  const std::size_t F = scene.mesh.num_faces();
  PriResult result;
  init_result(&result, F, options);
  std::vector<std::uint8_t> seen(F, 0);
  for (const PriPart& part : parts) {
    if (part.values.pri.size() != part.faces.size() || part.values.evidence_key.size() != part.faces.size() ||
        (options.measure == Measure::Offset) != !part.values.offset_signed.empty())
      throw Error("a PRI part's values do not match its faces or the measure");
    for (std::size_t j = 0; j < part.faces.size(); ++j) {
      const std::uint32_t f = part.faces[j];
      if (f >= F || seen[f]) throw Error("a PRI part holds face " + std::to_string(f) + " twice or out of range");
      seen[f] = 1;
      copy_face(part.values, j, &result, f);
    }
    result.recomputed += part.values.recomputed;
    result.images_decoded += part.values.images_decoded;
    result.views_used = std::max(result.views_used, part.values.views_used);
    result.views_reduced = std::max(result.views_reduced, part.values.views_reduced);
  }
  const std::size_t missing = std::size_t(std::count(seen.begin(), seen.end(), std::uint8_t(0)));
  if (missing) throw Error("the PRI parts miss " + std::to_string(missing) + " of " + std::to_string(F) + " faces");
  if (options.measure == Measure::Offset) {
    tbb::task_arena arena(thread_count(options));
    arena.execute([&] { smooth_offsets(scene.mesh, options, &result); });
  }
  count_statuses(&result);
  return result;
}

PriResult compute_pri(const Scene& scene, const PriOptions& options,
                      const ProgressCallback& progress) {
  return compute_pri(scene, options, progress, nullptr);
}

namespace {

// A face's vertex positions, in order, as a hashable key.
struct FaceGeometry {
  std::array<double, 9> x;
  bool operator==(const FaceGeometry& o) const {
    return std::memcmp(x.data(), o.x.data(), sizeof x) == 0;
  }
};
struct FaceGeometryHash {
  std::size_t operator()(const FaceGeometry& g) const {
    std::uint64_t h = 0;
    for (double v : g.x) h = combine(h, v);
    return std::size_t(h);
  }
};
FaceGeometry face_geometry(const TriangleMesh& mesh, std::size_t f) {
  FaceGeometry g;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) g.x[std::size_t(3 * k + c)] = mesh.vertices[mesh.faces[f][k]][c];
  return g;
}

}  // namespace

namespace {

// The 2-D bounding rectangle (u0, v0, u1, v1) of the projection of `box`
// into a camera without lens distortion, and the depth range of its
// corners (z0, z1: a point of the box is at a depth in between); false when
// it is unbounded (a corner behind the camera) or the camera distorts.
bool projected_rect(const PinholeCamera& c, const BoundingBox& box, std::array<double, 6>* rect) {
  if (c.has_distortion()) return false;
  constexpr double inf = std::numeric_limits<double>::infinity();
  *rect = {inf, inf, -inf, -inf, inf, -inf};
  for (const Vec3& corner : box.corners()) {
    const Vec3 x = c.R * corner + c.t;
    if (!(x.z() > 0)) return false;
    const double u = c.fx * x.x() / x.z() + c.skew * x.y() / x.z() + c.cx, v = c.fy * x.y() / x.z() + c.cy;
    (*rect)[0] = std::min((*rect)[0], u);
    (*rect)[1] = std::min((*rect)[1], v);
    (*rect)[2] = std::max((*rect)[2], u);
    (*rect)[3] = std::max((*rect)[3], v);
    (*rect)[4] = std::min((*rect)[4], x.z());
    (*rect)[5] = std::max((*rect)[5], x.z());
  }
  return true;
}

// Whether the segments from the camera to the points of tile box `t` may
// meet edit box `e`: their projections overlap (with `margin` pixels), and
// the edit is not wholly farther than the tile (a segment ends at its point).
bool may_occlude(const std::array<double, 6>& t, const std::array<double, 6>& e, double margin) {
  return t[0] <= e[2] + margin && e[0] <= t[2] + margin && t[1] <= e[3] + margin && e[1] <= t[3] + margin &&
         e[4] <= t[5] * (1 + 1e-9);
}

// Bounding boxes of groups of triangles (given by their corners), grouped
// along a Morton curve so that a local edit gives a few small boxes.
std::vector<BoundingBox> triangle_groups(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::vector<BoundingBox> boxes;
  if (triangles.empty()) return boxes;
  TriangleMesh soup;
  for (const auto& t : triangles) {
    const int base = int(soup.vertices.size());
    for (const Vec3& p : t) soup.vertices.push_back(p);
    soup.faces.push_back({base, base + 1, base + 2});
  }
  constexpr std::size_t kGroup = 256;
  for (const auto& group : pri_tiles(soup, (triangles.size() + kGroup - 1) / kGroup)) {
    BoundingBox b;
    for (std::uint32_t f : group)
      for (int k = 0; k < 3; ++k) b.extend(soup.vertices[std::size_t(soup.faces[f][k])]);
    boxes.push_back(b);
  }
  return boxes;
}

bool same_box(const BoundingBox& a, const BoundingBox& b) {
  return std::memcmp(a.min.data(), b.min.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.max.data(), b.max.data(), 3 * sizeof(double)) == 0;
}

// Whether `old` comes in the same order within `now` (views added, none
// removed or changed).
bool is_subsequence(const std::vector<std::uint64_t>& old, const std::vector<std::uint64_t>& now) {
  std::size_t j = 0;
  for (std::size_t i = 0; i < now.size() && j < old.size(); ++i)
    if (now[i] == old[j]) ++j;
  return j == old.size();
}

}  // namespace

PriReuse plan_incremental_pri(const Scene& scene, const PriOptions& options, const PriPrevious& previous,
                              const ProgressCallback& progress, const RayCaster* caster) {
  const PriResult& old = previous.result;
  const std::size_t G = previous.mesh.num_faces();
  if (old.pri.size() != G || old.evidence_key.size() != G)
    throw Error("the previous PRI does not hold one value and evidence key per face of its mesh");
  if ((options.measure == Measure::Offset) && old.offset_signed.size() != G)
    throw Error("the previous PRI has no offset-measure values (computed with another measure)");
  const TriangleMesh& mesh = scene.mesh;
  const std::size_t F = mesh.num_faces();
  // The views and their keys (select_pri_views' checks), no face yet.
  const PriViewSelection views = select_pri_views(scene, options, {}, {}, nullptr, true);

  // Faces of the new mesh with an identical face in the previous one: first
  // the face at the same index (an edit usually keeps the face list), then
  // the rest by geometry.
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> match(F, kNone);
  std::vector<std::uint8_t> old_matched(G, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, std::min(F, G)), [&](const auto& r) {
    for (std::size_t f = r.begin(); f < r.end(); ++f)
      if (old.evidence_key[f] != 0 && face_geometry(mesh, f) == face_geometry(previous.mesh, f)) {
        match[f] = std::uint32_t(f);
        old_matched[f] = 1;
      }
  });
  {
    std::unordered_map<FaceGeometry, std::uint32_t, FaceGeometryHash> by_geometry;
    for (std::size_t g = 0; g < G; ++g)
      if (!old_matched[g] && old.evidence_key[g] != 0) by_geometry.emplace(face_geometry(previous.mesh, g), std::uint32_t(g));
    if (!by_geometry.empty())
      for (std::size_t f = 0; f < F; ++f) {
        if (match[f] != kNone) continue;
        const auto it = by_geometry.find(face_geometry(mesh, f));
        if (it == by_geometry.end()) continue;
        match[f] = it->second;
        old_matched[it->second] = 1;
      }
  }

  // The faces whose views must be selected again.
  std::vector<std::uint8_t> suspect(F, 0);
  for (std::size_t f = 0; f < F; ++f) suspect[f] = match[f] == kNone;
  const bool keep_selection = old.options_key == views.options_key && !old.view_keys.empty() &&
                              is_subsequence(old.view_keys, views.view_keys) &&
                              same_box(mesh.bounding_box(), previous.mesh.bounding_box());
  if (!keep_selection) {
    std::fill(suspect.begin(), suspect.end(), std::uint8_t(1));
  } else {
    std::vector<std::array<Vec3, 3>> edited;
    for (std::size_t f = 0; f < F; ++f)
      if (match[f] == kNone)
        edited.push_back({mesh.vertices[mesh.faces[f][0]], mesh.vertices[mesh.faces[f][1]], mesh.vertices[mesh.faces[f][2]]});
    for (std::size_t g = 0; g < G; ++g)
      if (!old_matched[g]) {
        const Face& t = previous.mesh.faces[g];
        edited.push_back({previous.mesh.vertices[t[0]], previous.mesh.vertices[t[1]], previous.mesh.vertices[t[2]]});
      }
    const std::vector<BoundingBox> edits = triangle_groups(edited);
    constexpr std::size_t kTileFaces = 256;
    const auto tiles = pri_tiles(mesh, (F + kTileFaces - 1) / kTileFaces);
    std::vector<BoundingBox> tile_boxes(tiles.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size()), [&](const auto& r) {
      for (std::size_t t = r.begin(); t < r.end(); ++t)
        for (std::uint32_t f : tiles[t])
          for (int k = 0; k < 3; ++k) tile_boxes[t].extend(mesh.vertices[mesh.faces[f][k]]);
    });
    const std::vector<Vec3> normals = mesh.face_normals();
    const double min_cosine = std::cos(options.max_incidence_angle * M_PI / 180.0);
    std::size_t j = 0;  // position in old.view_keys
    for (std::size_t i = 0; i < views.cameras.size(); ++i) {
      const bool added = !(j < old.view_keys.size() && old.view_keys[j] == views.view_keys[i]);
      if (!added) ++j;
      const PinholeCamera& cam = views.cameras[i];
      const Vec3 centre = cam.center();
      std::vector<std::array<double, 6>> edit_rects;
      bool unbounded = false;
      for (const BoundingBox& b : edits) {
        if (!may_see_box(cam, b)) continue;  // the edit is out of this view
        std::array<double, 6> r;
        if (!projected_rect(cam, b, &r)) unbounded = true;
        else edit_rects.push_back(r);
      }
      if (!added && !unbounded && edit_rects.empty()) continue;
      // Tile by tile (a face is in one tile: no two threads write one flag).
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size()), [&](const auto& range) {
        std::vector<const std::array<double, 6>*> near;
        for (std::size_t t = range.begin(); t < range.end(); ++t) {
          if (!may_see_box(cam, tile_boxes[t])) continue;
          // A segment from the camera to a point of a face projects to that
          // point's pixel: an edit can hide it only where their projections
          // meet and the edit is not wholly behind it.
          near.clear();
          bool all = added || unbounded;
          std::array<double, 6> r;
          if (!all && !projected_rect(cam, tile_boxes[t], &r)) all = true;
          if (!all) {
            for (const auto& e : edit_rects)
              if (may_occlude(r, e, 2.0)) near.push_back(&e);
            if (near.empty()) continue;
          }
          for (std::uint32_t f : tiles[t]) {
            if (suspect[f]) continue;
            // A view the face cannot take whatever hides it (select_views'
            // own tests: a corner outside the image, facing away, grazing).
            const Face& face = mesh.faces[f];
            bool in = true;
            for (int k = 0; k < 3 && in; ++k) {
              Vec2 px;
              in = cam.project(mesh.vertices[face[k]], &px) && cam.in_image(px);
            }
            if (!in) continue;
            const Vec3 centroid = mesh.face_centroid(f);
            if (!(normals[f].dot(centre - centroid) > 0)) continue;
            if (normals[f].dot((centre - centroid).normalized()) < min_cosine) continue;
            if (all) {
              suspect[f] = 1;
              continue;
            }
            BoundingBox fb;
            for (int k = 0; k < 3; ++k) fb.extend(mesh.vertices[face[k]]);
            std::array<double, 6> fr;
            if (!projected_rect(cam, fb, &fr)) {
              suspect[f] = 1;
              continue;
            }
            for (const auto* e : near)
              if (may_occlude(fr, *e, 2.0)) {
                suspect[f] = 1;
                break;
              }
          }
        }
      });
    }
  }
  std::vector<std::uint32_t> again;
  for (std::size_t f = 0; f < F; ++f)
    if (suspect[f]) again.push_back(std::uint32_t(f));

  PriReuse out;
  out.selected = again.size();
  PriViewSelection& changed = out.changed;
  changed.image_views = views.image_views;
  changed.cameras = views.cameras;
  changed.view_keys = views.view_keys;
  changed.reductions = views.reductions;
  changed.options_key = views.options_key;
  PriViewSelection selection;
  if (!again.empty()) selection = select_pri_views(scene, options, progress, again, caster);
  std::vector<std::uint32_t> from;  // previous face of each reused face
  std::size_t j = 0;                // position in `again`
  for (std::size_t f = 0; f < F; ++f) {
    if (!suspect[f]) {  // its selection is the previous one: so is its key
      out.reused.faces.push_back(std::uint32_t(f));
      from.push_back(match[f]);
      continue;
    }
    const PriFaceViews& fv = selection.faces[j++];
    // The key score_block would give the face now.
    std::uint64_t key = views.options_key;
    for (int v : fv.views) key = combine(key, view_evidence(views, std::size_t(v)));
    if (match[f] != kNone && old.evidence_key[match[f]] == key) {
      out.reused.faces.push_back(std::uint32_t(f));
      from.push_back(match[f]);
      continue;
    }
    changed.face_ids.push_back(std::uint32_t(f));
    changed.faces.push_back(fv);
  }
  init_result(&out.reused.values, out.reused.faces.size(), options);
  for (std::size_t k = 0; k < from.size(); ++k) copy_face(old, from[k], &out.reused.values, k);
  out.reused.values.views_used = views.image_views.size();
  return out;
}

PriResult compute_pri(const Scene& scene, const PriOptions& options, const ProgressCallback& progress,
                      const PriPrevious* previous) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<PriPart> parts;
  std::vector<std::uint64_t> view_keys;
  std::size_t views_used = 0, reselected = 0;
  if (previous) {
    PriReuse reuse = plan_incremental_pri(scene, options, *previous, progress);
    reselected = reuse.selected;
    view_keys = reuse.changed.view_keys;
    views_used = reuse.changed.image_views.size();
    parts.push_back(std::move(reuse.reused));
    // No changed face: an empty selection would mean "every face".
    if (!reuse.changed.faces.empty()) parts.push_back(compute_pri_part(scene, options, reuse.changed, progress));
  } else {
    const PriViewSelection selection = select_pri_views(scene, options, progress);
    reselected = selection.faces.size();
    view_keys = selection.view_keys;
    views_used = selection.image_views.size();
    parts.push_back(compute_pri_part(scene, options, selection, progress));
  }
  PriResult result = assemble_pri(scene, options, parts);
  result.views_used = views_used;
  result.view_keys = view_keys;
  result.options_key = pri_options_key(options);
  result.reselected = reselected;
  report_progress(progress, 1.0, "pri");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<Rgb8> pri_colors(const std::vector<float>& pri, double lo, double hi) {
  std::vector<Rgb8> out(pri.size());
  const double span = hi > lo ? hi - lo : 1.0;
  for (std::size_t f = 0; f < pri.size(); ++f) {
    if (std::isnan(pri[f])) {
      out[f] = {160, 160, 160};
      continue;
    }
    // Hue 120 (green, best) .. 0 (red, worst), full saturation and value.
    const double t = std::clamp((pri[f] - lo) / span, 0.0, 1.0);
    const double hue = 120.0 * (1.0 - t);
    const double x = 1.0 - std::abs(std::fmod(hue / 60.0, 2.0) - 1.0);
    double r = 0, g = 0;
    if (hue < 60) r = 1, g = x;
    else r = x, g = 1;
    out[f] = {std::uint8_t(std::lround(255 * r)), std::uint8_t(std::lround(255 * g)), 0};
  }
  return out;
}

PriSummary summarize_pri(const PriResult& result, std::size_t worst_k, int bins) {
  PriSummary s;
  s.faces = result.pri.size();
  s.observed = result.observed;
  s.unobserved = result.unobserved;
  s.textureless = result.textureless;
  std::vector<std::pair<float, int>> values;
  for (std::size_t f = 0; f < result.pri.size(); ++f)
    if (!std::isnan(result.pri[f])) values.emplace_back(result.pri[f], int(f));
  if (values.empty()) return s;
  std::vector<float> sorted;  // reordered by the percentiles
  sorted.reserve(values.size());
  for (const auto& v : values) sorted.push_back(v.first);
  s.percentiles = detail::interpolated_percentiles(sorted, {0.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0, 100.0});
  const auto [lowest, highest] = std::minmax_element(sorted.begin(), sorted.end());
  s.histogram_min = *lowest;
  s.histogram_max = *highest;
  s.histogram.assign(std::size_t(std::max(1, bins)), 0);
  const double width = (s.histogram_max - s.histogram_min) / double(s.histogram.size());
  for (float v : sorted) {
    std::size_t b = width > 0 ? std::size_t((v - s.histogram_min) / width) : 0;
    ++s.histogram[std::min(b, s.histogram.size() - 1)];
  }
  // Worst first; ties by face id for determinism.
  const std::size_t k_worst = std::min(worst_k, values.size());
  std::partial_sort(values.begin(), values.begin() + std::ptrdiff_t(k_worst), values.end(),
                    [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  for (std::size_t k = 0; k < std::min(worst_k, values.size()); ++k)
    s.worst.push_back({values[k].second, values[k].first, result.pri_views[std::size_t(values[k].second)]});
  return s;
}

}  // namespace meshnbv
