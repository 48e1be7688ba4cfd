#include "meshnbv/gain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "meshnbv/enum_names.h"
#include "meshnbv/error.h"
#include "meshnbv/hull.h"
#include "meshnbv/pri.h"

namespace meshnbv {

namespace {

constexpr detail::EnumTable<EnergyKind, 2> kEnergyKinds = {
    {"paper", EnergyKind::Paper},
    {"reconstructability", EnergyKind::Reconstructability},
};

double sigmoid(double x, double x0, double k) { return 1.0 / (1.0 + std::exp(-k * (x - x0))); }

// A function of the angle alpha tabulated over cos(alpha) on [-1, 1] in
// 8192 cells and interpolated linearly: the pair loop's only
// transcendentals (the energy agrees with the exact formula to 1e-4
// relative: test_gain.cpp).
class AngleTable {
 public:
  static constexpr int kCells = 8192;
  template <class F>
  explicit AngleTable(F f) {
    for (int i = 0; i <= kCells; ++i) {
      const double c = -1.0 + 2.0 * i / kCells;
      values_[std::size_t(i)] = f(std::acos(std::clamp(c, -1.0, 1.0)));
    }
    for (double v : values_) max_ = std::max(max_, v);
  }
  double operator()(double cos_alpha) const {
    const double u = (std::clamp(cos_alpha, -1.0, 1.0) + 1.0) * (0.5 * kCells);
    const int i = std::min(int(u), kCells - 1);
    const double w = u - i;
    return (1 - w) * values_[std::size_t(i)] + w * values_[std::size_t(i) + 1];
  }
  double max() const { return max_; }

 private:
  std::array<double, kCells + 1> values_{};
  double max_ = 0;
};

const AngleTable& pair_table() {
  static const AngleTable table(pair_angle_score);
  return table;
}

// The triangulation sigmoid alone: how far a new ray is from being a
// repeat of the nearest existing one.
const AngleTable& novelty_table() {
  static const AngleTable table([](double a) { return sigmoid(a, M_PI / 16, 32); });
  return table;
}

// Faces with an edge no other face shares.
std::vector<char> boundary_faces(const TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, int> edges;
  edges.reserve(mesh.num_faces() * 3);
  auto key = [](std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
  };
  for (const Face& f : mesh.faces)
    for (int k = 0; k < 3; ++k) ++edges[key(std::uint32_t(f[k]), std::uint32_t(f[(k + 1) % 3]))];
  std::vector<char> out(mesh.num_faces(), 0);
  for (std::size_t i = 0; i < mesh.num_faces(); ++i) {
    const Face& f = mesh.faces[i];
    for (int k = 0; k < 3; ++k)
      if (edges[key(std::uint32_t(f[k]), std::uint32_t(f[(k + 1) % 3]))] == 1) out[i] = 1;
  }
  return out;
}

// Rank of each observed face's PRI among the observed faces, in (0, 1]
// (ties share their mean rank; the highest PRI 1); NaN where unobserved.
std::vector<double> pri_quantiles(const std::vector<float>& pri) {
  std::vector<std::size_t> order;
  for (std::size_t f = 0; f < pri.size(); ++f)
    if (std::isfinite(pri[f])) order.push_back(f);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pri[a] != pri[b] ? pri[a] < pri[b] : a < b;
  });
  std::vector<double> q(pri.size(), std::nan(""));
  const double n = double(order.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j < order.size() && pri[order[j]] == pri[order[i]]) ++j;
    const double rank = 0.5 * double(i + 1 + j);  // mean of the ranks i+1..j
    for (std::size_t k = i; k < j; ++k) q[order[k]] = rank / n;
    i = j;
  }
  return q;
}

// The dominant axis of a normal, with its sign: 0..5.
int normal_bin(const Vec3& n) {
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  return 2 * axis + (n[axis] < 0 ? 1 : 0);
}

}  // namespace

EnergyKind parse_energy_kind(const std::string& name) {
  return detail::parse_enum(name, kEnergyKinds, "energy");
}

std::string energy_kind_name(EnergyKind kind) { return detail::enum_name(kind, kEnergyKinds); }

double pair_angle_score(double alpha) {
  return (1.0 - sigmoid(alpha, M_PI / 4, 8)) * sigmoid(alpha, M_PI / 16, 32);
}

GainEvaluator::GainEvaluator(const TriangleMesh& mesh, const RayCaster& caster, const std::vector<float>& pri,
                             const std::vector<PinholeCamera>& existing, const GainOptions& options)
    : mesh_(mesh), caster_(caster), options_(options) {
  const std::size_t F = mesh.num_faces();
  if (pri.size() != F)
    throw Error("PRI has " + std::to_string(pri.size()) + " values for " + std::to_string(F) + " faces");
  if (F == 0) throw Error("the mesh has no faces");
  cos_max_incidence_ = std::cos(options.max_incidence * M_PI / 180.0);
  cos_match_ = options.match_angle >= 180 ? -2.0 : std::cos(options.match_angle * M_PI / 180.0);
  const double diagonal = mesh.bounding_box().diagonal();
  absolute_eps_ = options.visibility.absolute_eps_of_diagonal * diagonal;

  // Face weights.
  const std::vector<double> q = pri_quantiles(pri);
  const std::vector<char> boundary = boundary_faces(mesh);
  const std::vector<double> area = mesh.face_areas();
  const double total_area = std::max(std::accumulate(area.begin(), area.end(), 0.0), 1e-300);
  weight_.assign(F, 0.0f);
  std::vector<char> explore(F, 0);
  for (std::size_t f = 0; f < F; ++f) {
    explore[f] = !std::isfinite(q[f]) || boundary[f];
    weight_[f] = float(explore[f] ? options.exploration_weight : q[f]);
  }

  // Clusters: Morton runs split by the normal's dominant axis.
  const std::vector<Vec3> normals = mesh.face_normals();
  std::vector<std::vector<int>> groups;
  if (options.clusters <= 0 || std::size_t(options.clusters) >= F) {
    for (std::size_t f = 0; f < F; ++f) groups.push_back({int(f)});
  } else {
    // About three bins of six are filled per run on typical surfaces.
    const std::size_t runs = std::max<std::size_t>(1, std::size_t(options.clusters) / 3);
    for (const auto& run : pri_tiles(mesh, runs)) {
      std::array<std::vector<int>, 6> bins;
      for (std::uint32_t f : run) bins[std::size_t(normal_bin(normals[f]))].push_back(int(f));
      for (auto& b : bins)
        if (!b.empty()) groups.push_back(std::move(b));
    }
  }
  clusters_.resize(groups.size());
  cluster_of_face_.assign(F, -1);
  for (std::size_t c = 0; c < groups.size(); ++c) {
    Cluster& k = clusters_[c];
    k.faces = std::move(groups[c]);
    Vec3 centroid = Vec3::Zero(), normal = Vec3::Zero();
    double a = 0;
    for (int f : k.faces) {
      cluster_of_face_[std::size_t(f)] = int(c);
      const double af = area[std::size_t(f)];
      k.area += af;
      centroid += af * mesh.face_centroid(std::size_t(f));
      normal += af * normals[std::size_t(f)];
      a += af;
      (explore[std::size_t(f)] ? k.weight_explore : k.weight_refine) += af * weight_[std::size_t(f)];
    }
    centroid = a > 0 ? Vec3(centroid / a) : mesh.face_centroid(std::size_t(k.faces[0]));
    int nearest = k.faces[0];
    double best = std::numeric_limits<double>::infinity();
    for (int f : k.faces) {
      const double d = (mesh.face_centroid(std::size_t(f)) - centroid).squaredNorm();
      if (d < best) best = d, nearest = f;
    }
    k.point = mesh.face_centroid(std::size_t(nearest));
    k.normal = normal.norm() > 0 ? Vec3(normal.normalized()) : normals[std::size_t(nearest)];
  }

  // The existing views of every cluster; d_max is twice the largest
  // distance at which an existing view sees a cluster (twice the diagonal
  // when none does).
  d_max_ = std::numeric_limits<double>::infinity();
  std::vector<std::vector<std::pair<Ray, double>>> seen(clusters_.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, clusters_.size()), [&](const auto& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c)
      for (const PinholeCamera& cam : existing) {
        Ray ray;
        if (view_ray(clusters_[c], cam, true, &ray))
          seen[c].push_back({ray, (cam.center() - clusters_[c].point).norm()});
      }
  });
  double far = 0;
  for (const auto& s : seen)
    for (const auto& [ray, d] : s) far = std::max(far, d);
  d_max_ = far > 0 ? 2 * far : 2 * std::max(diagonal, 1e-300);
  for (std::size_t c = 0; c < clusters_.size(); ++c) {
    Cluster& k = clusters_[c];
    for (auto& [ray, d] : seen[c]) {
      ray.scale = 1 - d / d_max_;
      k.h += delta(k, ray);
      k.best_single = std::max(k.best_single, ray.cos_theta * ray.scale);
      k.rays.push_back(ray);
    }
  }
  double unknown_area = 0;
  if (options.explore_hull) unknown_area = add_hull_proxy(existing);
  // Weights as shares of the surface: the mesh's area and the unknown part
  // of the hull's.
  const double scale = 1.0 / (total_area + unknown_area);
  for (Cluster& k : clusters_) k.weight_refine *= scale, k.weight_explore *= scale;
}

double GainEvaluator::add_hull_proxy(const std::vector<PinholeCamera>& existing) {
  // The mesh's vertices without the farthest 1% from their per-axis median
  // (stray faces of a sparse reconstruction would inflate the hull).
  std::vector<char> used(mesh_.num_vertices(), 0);
  for (const Face& f : mesh_.faces)
    for (int k = 0; k < 3; ++k) used[std::size_t(f[k])] = 1;
  std::vector<Vec3> points;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) points.push_back(mesh_.vertices[v]);
  if (points.size() < 4) return 0;
  Vec3 centre;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> x(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) x[i] = points[i][a];
    std::nth_element(x.begin(), x.begin() + std::ptrdiff_t(x.size() / 2), x.end());
    centre[a] = x[x.size() / 2];
  }
  std::vector<double> d(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) d[i] = (points[i] - centre).norm();
  std::vector<double> sorted = d;
  const std::size_t q = std::min(sorted.size() - 1, std::size_t(0.99 * double(sorted.size())));
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(q), sorted.end());
  const double limit = sorted[q];
  std::vector<Vec3> kept;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (d[i] <= limit) kept.push_back(points[i]);
  const std::vector<HullTriangle> hull = convex_hull_triangles(kept);
  if (hull.empty()) return 0;

  // Points on the hull, about half as many as the mesh has clusters, each
  // the centroid of a sub-triangle of its hull face.
  double hull_area = 0;
  for (const HullTriangle& t : hull) hull_area += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
  const std::size_t wanted = std::clamp<std::size_t>(clusters_.size() / 2, 64, 100000);
  const double cell = hull_area / double(wanted);
  const double spacing = std::sqrt(cell);
  struct Sample {
    Vec3 point, normal;
    double area;
  };
  std::vector<Sample> samples;
  for (const HullTriangle& t : hull) {
    const Vec3 cross = (t[1] - t[0]).cross(t[2] - t[0]);
    const double area = 0.5 * cross.norm();
    if (!(area > 0)) continue;
    const Vec3 normal = cross.normalized();
    const int n = std::max(1, int(std::ceil(std::sqrt(area / cell))));
    const double sub = area / (double(n) * n);
    auto at = [&](double u, double v) { return Vec3(t[0] + (u / n) * (t[1] - t[0]) + (v / n) * (t[2] - t[0])); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        samples.push_back({at(i + 1.0 / 3, j + 1.0 / 3), normal, sub});
        if (i + j < n - 1) samples.push_back({at(i + 2.0 / 3, j + 2.0 / 3), normal, sub});
      }
  }
  // Unknown: farther from the mesh than the spacing (where the hull lies
  // on the mesh, the mesh speaks for itself) and seen by no existing view.
  std::vector<char> unknown(samples.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size()), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (caster_.closest_point(samples[i].point) < spacing) continue;
      Cluster probe;
      probe.point = samples[i].point;
      probe.normal = samples[i].normal;
      bool seen = false;
      Ray ray;
      for (const PinholeCamera& cam : existing)
        if (view_ray(probe, cam, true, &ray)) {
          seen = true;
          break;
        }
      unknown[i] = !seen;
    }
  });
  double unknown_area = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!unknown[i]) continue;
    Cluster k;
    k.point = samples[i].point;
    k.normal = samples[i].normal;
    k.area = samples[i].area;
    k.weight_explore = samples[i].area * options_.exploration_weight;
    clusters_.push_back(std::move(k));
    unknown_area += samples[i].area;
    ++num_proxy_;
  }
  return unknown_area;
}

bool GainEvaluator::view_ray(const Cluster& c, const PinholeCamera& camera, bool check_occlusion,
                             Ray* ray) const {
  const Vec3 centre = camera.center();
  const Vec3 d = centre - c.point;
  const double dist = d.norm();
  if (!(dist > 0) || !(dist < d_max_)) return false;
  const Vec3 u = d / dist;
  const double cos_theta = u.dot(c.normal);
  if (!(cos_theta > cos_max_incidence_)) return false;
  Vec2 px;
  if (!camera.project(c.point, &px) || !camera.in_image(px)) return false;
  if (check_occlusion &&
      !caster_.segment_clear(centre, c.point, options_.visibility.relative_eps, absolute_eps_))
    return false;
  ray->direction = u;
  ray->cos_theta = cos_theta;
  ray->scale = std::isfinite(d_max_) ? 1 - dist / d_max_ : 1.0;
  return true;
}

double GainEvaluator::delta(const Cluster& c, const Ray& r) const { return matched_delta(c, r, 1.0, false); }

double GainEvaluator::matched_delta(const Cluster& c, const Ray& r, double share, bool gate) const {
  const AngleTable& g = pair_table();
  double sum = 0, nearest = -1;  // cos of the smallest angle to an existing ray
  for (const Ray& v : c.rays) {
    const double cos_alpha = r.direction.dot(v.direction);
    sum += g(cos_alpha) * std::min(r.cos_theta, v.cos_theta) * std::min(r.scale, v.scale);
    nearest = std::max(nearest, cos_alpha);
  }
  // The first-view credit: half an ideal pair, the best one over the views.
  sum += 0.5 * g.max() * std::max(0.0, r.cos_theta * r.scale - c.best_single);
  if (c.rays.empty()) return gate ? share * sum : sum;
  // Beyond the match angle of every existing ray, nothing is matched.
  if (gate && nearest < cos_match_) return 0;
  // A ray within a few degrees of one already there repeats it.
  return novelty_table()(nearest) * sum;
}

double GainEvaluator::matched_share(const PinholeCamera& candidate) const {
  if (cos_match_ < -1) return 1;
  const std::size_t stride = std::max<std::size_t>(1, (clusters_.size() + 255) / 256);
  double seen = 0, matched = 0;
  for (std::size_t c = 0; c < clusters_.size(); c += stride) {
    const Cluster& k = clusters_[c];
    Ray ray;
    if (!view_ray(k, candidate, false, &ray)) continue;
    seen += k.area;
    for (const Ray& v : k.rays)
      if (ray.direction.dot(v.direction) >= cos_match_) {
        matched += k.area;
        break;
      }
  }
  return seen > 0 ? matched / seen : 0;
}

double GainEvaluator::weighted_gain(const Cluster& c, double dh) const {
  const double T = options_.target;
  const double before = std::max(T - c.h, 0.0), after = std::max(T - c.h - dh, 0.0);
  return (c.weight_refine + c.weight_explore) * (before * before - after * after) / (T * T);
}

template <class F>
void GainEvaluator::for_each_gain(const PinholeCamera& candidate, F&& f) const {
  const double share = matched_share(candidate);
  for (std::size_t c = 0; c < clusters_.size(); ++c) {
    const Cluster& k = clusters_[c];
    if (k.h >= options_.target || k.weight_refine + k.weight_explore <= 0) continue;
    Ray ray;
    if (!view_ray(k, candidate, false, &ray)) continue;
    const double gain = weighted_gain(k, matched_delta(k, ray, share, true));
    if (!(gain > 0)) continue;
    // The occlusion ray last: only for a cluster that would gain.
    if (!caster_.segment_clear(candidate.center(), k.point, options_.visibility.relative_eps, absolute_eps_))
      continue;
    f(c, gain);
  }
}

std::vector<std::pair<int, double>> GainEvaluator::cluster_gains(const PinholeCamera& candidate) const {
  std::vector<std::pair<int, double>> out;
  for_each_gain(candidate, [&](std::size_t c, double gain) { out.push_back({int(c), gain}); });
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

EnergyTerms GainEvaluator::evaluate(const PinholeCamera& candidate) const {
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  EnergyTerms t;
  t.whole_mesh = true;
  for_each_gain(candidate, [&](std::size_t c, double gain) {
    const Cluster& k = clusters_[c];
    const double share = k.weight_refine / (k.weight_refine + k.weight_explore);
    t.refinement += gain * share;
    t.exploration += gain * (1 - share);
  });
  t.total = t.refinement + t.exploration;
  return t;
}

std::vector<int> GainEvaluator::improved_faces(const PinholeCamera& candidate, std::size_t max_faces) const {
  std::vector<int> faces;
  for (const auto& [c, gain] : cluster_gains(candidate)) {
    for (int f : clusters_[std::size_t(c)].faces) {
      if (faces.size() >= max_faces) return faces;
      faces.push_back(f);
    }
  }
  return faces;
}

void GainEvaluator::add_view(const PinholeCamera& camera) {
  const double share = matched_share(camera);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, clusters_.size()), [&](const auto& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      Cluster& k = clusters_[c];
      Ray ray;
      if (!view_ray(k, camera, true, &ray)) continue;
      k.h += matched_delta(k, ray, share, true);
      k.best_single = std::max(k.best_single, ray.cos_theta * ray.scale);
      k.rays.push_back(ray);
    }
  });
}

std::vector<float> GainEvaluator::face_deficits() const {
  std::vector<float> out(mesh_.num_faces(), 0.0f);
  for (const Cluster& k : clusters_) {
    const double d = std::max(options_.target - k.h, 0.0) / options_.target;
    for (int f : k.faces) out[std::size_t(f)] = float(weight_[std::size_t(f)] * d * d);
  }
  return out;
}

std::vector<float> GainEvaluator::face_reconstructability() const {
  std::vector<float> out(mesh_.num_faces(), 0.0f);
  for (const Cluster& k : clusters_)
    for (int f : k.faces) out[std::size_t(f)] = float(k.h);
  return out;
}

}  // namespace meshnbv
