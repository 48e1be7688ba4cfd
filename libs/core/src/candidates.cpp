#include "meshnbv/candidates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include <Eigen/Eigenvalues>

#include "meshnbv/options.h"
#include "meshnbv/planner.h"
#include "meshnbv/error.h"

namespace meshnbv {

SafetyChecker::SafetyChecker(const TriangleMesh& mesh, const RayCaster& caster, double distance)
    : mesh_(mesh), caster_(caster), distance_(distance) {
  const double diagonal = mesh.bounding_box().diagonal();
  step_ = 1e-6 * std::max(1e-300, diagonal);
  // Distances to a surface of zero-area faces only would be meaningless.
  bool any_area = false;
  for (std::size_t f = 0; f < mesh.faces.size() && !any_area; ++f)
    any_area = mesh.face_area(f) > 1e-14 * diagonal * diagonal;
  if (!any_area) throw Error("the surface has no non-degenerate face");
}

void SafetyChecker::set_ground(const Vec3& up, double height) {
  if (!(up.allFinite() && std::abs(up.norm() - 1) < 1e-6) || !std::isfinite(height))
    throw Error("the ground needs a unit up direction and a finite height");
  has_ground_ = true;
  up_ = up;
  ground_ = height;
}

double ground_height(const TriangleMesh& mesh, const Vec3& up) {
  if (mesh.vertices.empty()) throw Error("the mesh has no vertices to take a ground height from");
  std::vector<double> h;
  h.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) h.push_back(up.dot(v));
  const std::size_t k = std::size_t(0.01 * double(h.size() - 1));
  std::nth_element(h.begin(), h.begin() + std::ptrdiff_t(k), h.end());
  return h[k];
}

bool SafetyChecker::inside_volume(const Vec3& p) const {
  // Three fixed, non-axis-aligned directions (axis-aligned rays would graze
  // the edges of axis-aligned walls).
  static const std::array<Vec3, 3> dirs = {Vec3(0.267, 0.534, 0.802).normalized(),
                                           Vec3(-0.623, 0.312, -0.717).normalized(),
                                           Vec3(0.401, -0.816, 0.416).normalized()};
  int inside = 0;
  for (const Vec3& d : dirs) {
    // Signed crossings from p to infinity: +1 leaving a solid, -1 entering.
    int winding = 0;
    double t = 0;
    RayHit hit;
    for (std::size_t k = 0; k <= mesh_.faces.size() && caster_.intersect(p, d, &hit, t); ++k) {
      winding += mesh_.face_normal(std::size_t(hit.face)).dot(d) > 0 ? 1 : -1;
      t = hit.distance + step_;
    }
    inside += winding > 0;
  }
  return inside >= 2;
}

double median_viewing_distance(const std::vector<PinholeCamera>& cameras, const RayCaster& caster,
                               const Vec3& fallback_target) {
  if (cameras.empty()) throw Error("no existing camera to take a viewing distance from");
  std::vector<double> d;
  for (const auto& c : cameras) {
    RayHit hit;
    if (caster.intersect(c.center(), c.forward(), &hit))
      d.push_back(hit.distance);
    else
      d.push_back((fallback_target - c.center()).norm());
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

Vec3 mean_up(const std::vector<PinholeCamera>& cameras) {
  Vec3 sum = Vec3::Zero();
  for (const auto& c : cameras) sum -= c.down();
  return sum.norm() > 1e-9 ? Vec3(sum.normalized()) : Vec3::UnitZ();
}

Vec3 level_up(const std::vector<PinholeCamera>& cameras) {
  const Vec3 m = mean_up(cameras);
  if (cameras.empty()) return m;
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  Vec3 mean_right = Vec3::Zero();
  for (const auto& c : cameras) {
    sum += c.right() * c.right().transpose();
    mean_right += c.right();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sum);
  // Ascending eigenvalues: the least is about 0 for level cameras; the
  // middle one says whether the right axes span a plane.
  if (eig.eigenvalues()(1) > 1e-3 * eig.eigenvalues()(2)) {
    Vec3 u = eig.eigenvectors().col(0).normalized();
    return u.dot(m) < 0 ? Vec3(-u) : u;
  }
  const Vec3 r = mean_right.norm() > 1e-9 ? Vec3(mean_right.normalized()) : Vec3::Zero();
  const Vec3 u = m - m.dot(r) * r;
  return u.norm() > 1e-9 ? Vec3(u.normalized()) : m;
}

PinholeCamera most_common_intrinsics(const std::vector<PinholeCamera>& cameras) {
  if (cameras.empty()) throw Error("no existing camera to take intrinsics from");
  std::map<std::tuple<double, double, double, double, int, int>, int> count;
  for (const auto& c : cameras) ++count[{c.fx, c.fy, c.cx, c.cy, c.width, c.height}];
  // Highest count; ties by the order of the first occurrence.
  const PinholeCamera* best = &cameras[0];
  int best_n = 0;
  for (const auto& c : cameras) {
    const int n = count[{c.fx, c.fy, c.cx, c.cy, c.width, c.height}];
    if (n > best_n) best = &c, best_n = n;
  }
  PinholeCamera out = *best;
  out.clear_lens();
  return out;
}

PinholeCamera camera_looking(const PinholeCamera& intr, const Vec3& centre, const Vec3& direction,
                             const Vec3& up) {
  const Vec3 d = direction.normalized();
  Vec3 u = up;
  if (std::abs(d.dot(u.normalized())) > 0.999) u = std::abs(d.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitY();
  return PinholeCamera::look_at(centre, centre + d, u, intr.fx, intr.fy, intr.cx, intr.cy,
                                intr.width, intr.height);
}

void SamplingOptions::check() const {
  // directions and seed: the suggest table's ranges (options.h).
  SuggestOptions as_suggest;
  as_suggest.sampling = *this;
  check_options(as_suggest, suggest_option_table());
  check_not_in_table();
}

void SamplingOptions::check_not_in_table() const {
  check_option(!distance_factors.empty() && distance_factors.size() <= 16,
               "the number of distance_factors", "in [1, 16]", double(distance_factors.size()));
  for (double f : distance_factors)
    check_option(f > 0 && f <= 100, "distance factor", "in (0, 100]", f);
}

void RefineOptions::check() const {
  // iterations: the suggest table's range (refine_iterations, options.h).
  SuggestOptions as_suggest;
  as_suggest.refine = *this;
  check_options(as_suggest, suggest_option_table());
  check_not_in_table();
}

void RefineOptions::check_not_in_table() const {
  check_option(position_step > 0 && position_step <= 10, "refine position_step", "in (0, 10]",
               position_step);
  check_option(angle_step > 0 && angle_step <= 90, "refine angle_step", "in (0, 90] degrees",
               angle_step);
}

CandidateSet sample_candidates(const WorstRegion& region, const PinholeCamera& intr, const Vec3& up,
                               double distance, const SafetyChecker& safety,
                               const SamplingOptions& o) {
  o.check();
  if (!(distance > 0)) throw Error("viewing distance must be positive");
  CandidateSet out;
  // Orthonormal frame around the region's normal.
  const Vec3 n = region.mean_normal;
  Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = n.cross(a).normalized(), e2 = n.cross(e1);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  // The seed turns the spiral about the normal (splitmix to an angle).
  std::uint64_t x = o.seed + 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  const double phase = double((x ^ (x >> 31)) >> 11) * 0x1.0p-53 * 2 * M_PI;
  for (int k = 0; k < o.directions; ++k) {
    // Heights (cosines) evenly in (0, 1]: the open hemisphere.
    const double h = 1.0 - (k + 0.5) / o.directions;
    const double r = std::sqrt(std::max(0.0, 1 - h * h));
    const double phi = golden * k + phase;
    const Vec3 dir = h * n + r * (std::cos(phi) * e1 + std::sin(phi) * e2);
    for (double factor : o.distance_factors) {
      ++out.generated;
      const Vec3 centre = region.centroid + factor * distance * dir;
      if (safety.below_ground(centre)) {
        ++out.rejected_below_ground;
        continue;
      }
      if (safety.too_close(centre)) {
        ++out.rejected_too_close;
        continue;
      }
      if (safety.inside_volume(centre)) {
        ++out.rejected_inside;
        continue;
      }
      out.cameras.push_back(camera_looking(intr, centre, region.centroid - centre, up));
    }
  }
  return out;
}

namespace {

using Params = std::array<double, 5>;  // x, y, z, yaw, pitch

struct PoseFrame {
  Vec3 forward, right, upv;
};

PinholeCamera pose(const PinholeCamera& start, const PoseFrame& f, const Vec3& up, const Params& p) {
  // Yaw about the start's up axis, then pitch about its right axis.
  const Vec3 yawed = std::cos(p[3]) * f.forward + std::sin(p[3]) * f.right;
  const Vec3 dir = std::cos(p[4]) * yawed + std::sin(p[4]) * f.upv;
  return camera_looking(start, Vec3(p[0], p[1], p[2]), dir, up);
}

}  // namespace

PinholeCamera refine_candidate(const PinholeCamera& start, const Vec3& up,
                               const EnergyEvaluator& energy, const SafetyChecker& safety,
                               const RefineOptions& o, std::size_t* evaluations) {
  return refine_candidate(
      start, up, [&](const PinholeCamera& c) { return energy.evaluate(c).total; }, energy.region().centroid,
      safety, o, evaluations);
}

PinholeCamera refine_candidate(const PinholeCamera& start, const Vec3& up,
                               const std::function<double(const PinholeCamera&)>& energy,
                               const Vec3& target, const SafetyChecker& safety, const RefineOptions& o,
                               std::size_t* evaluations) {
  o.check();
  const Vec3 c0 = start.center();
  std::size_t evaluated = 0;
  PoseFrame frame{start.forward(), start.right(), -start.down()};
  const double scale = std::max(1e-9, (target - c0).norm());
  auto cost = [&](const Params& p) {
    const Vec3 c(p[0], p[1], p[2]);
    if (!safety.safe(c)) return std::numeric_limits<double>::infinity();
    ++evaluated;
    return -energy(pose(start, frame, up, p));
  };
  // Nelder-Mead (standard coefficients), 6 vertices in 5-D.
  std::array<Params, 6> s;
  std::array<double, 6> f;
  s[0] = {c0.x(), c0.y(), c0.z(), 0.0, 0.0};
  const double steps[5] = {o.position_step * scale, o.position_step * scale,
                           o.position_step * scale, o.angle_step * M_PI / 180,
                           o.angle_step * M_PI / 180};
  for (int i = 1; i < 6; ++i) {
    s[i] = s[0];
    s[i][i - 1] += steps[i - 1];
  }
  for (int i = 0; i < 6; ++i) f[i] = cost(s[i]);
  const double f_start = f[0];
  for (int it = 0; it < o.iterations; ++it) {
    std::array<int, 6> idx = {0, 1, 2, 3, 4, 5};
    std::sort(idx.begin(), idx.end(), [&](int a, int b) { return f[a] < f[b]; });
    const int best = idx[0], worst = idx[5], second = idx[4];
    Params centroid{};
    for (int i = 0; i < 5; ++i)
      for (int d = 0; d < 5; ++d) centroid[d] += s[idx[i]][d] / 5.0;
    auto along = [&](double t) {
      Params p;
      for (int d = 0; d < 5; ++d) p[d] = centroid[d] + t * (s[worst][d] - centroid[d]);
      return p;
    };
    const Params xr = along(-1.0);
    const double fr = cost(xr);
    if (fr < f[best]) {
      const Params xe = along(-2.0);
      const double fe = cost(xe);
      if (fe < fr) s[worst] = xe, f[worst] = fe;
      else s[worst] = xr, f[worst] = fr;
    } else if (fr < f[second]) {
      s[worst] = xr, f[worst] = fr;
    } else {
      const Params xc = fr < f[worst] ? along(-0.5) : along(0.5);
      const double fc = cost(xc);
      if (fc < std::min(fr, f[worst])) {
        s[worst] = xc, f[worst] = fc;
      } else {
        for (int i = 1; i < 6; ++i) {  // shrink towards the best
          const int k = idx[i];
          for (int d = 0; d < 5; ++d) s[k][d] = s[best][d] + 0.5 * (s[k][d] - s[best][d]);
          f[k] = cost(s[k]);
        }
      }
    }
  }
  if (evaluations) *evaluations = evaluated;
  const int best = int(std::min_element(f.begin(), f.end()) - f.begin());
  if (!(f[best] < f_start)) return start;  // never worse than where it began
  return pose(start, frame, up, s[best]);
}

}  // namespace meshnbv
