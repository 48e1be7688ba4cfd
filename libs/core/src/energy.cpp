#include "meshnbv/energy.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "meshnbv/options.h"
#include "meshnbv/planner.h"
#include "meshnbv/error.h"

namespace meshnbv {

namespace {
constexpr double kDeg = M_PI / 180.0;

// kappa cos(d) - log(2 pi I0(kappa)) = kappa (cos d - 1) - (log(2 pi I0) - kappa),
// with cos d - 1 = -2 sin^2(d / 2): no overflow and no cancellation of two
// large numbers for large kappa.
double von_mises_log_density(double d, double kappa, double log_norm_scaled) {
  const double s = std::sin(0.5 * d);
  return -2.0 * kappa * s * s - log_norm_scaled;
}
}  // namespace

double log_bessel_i0_scaled(double kappa) {
  if (kappa < kBesselI0AsymptoticFrom) return std::log(std::cyl_bessel_i(0.0, kappa)) - kappa;
  // Hankel's asymptotic series: term_j = term_{j-1} (2j-1)^2 / (8 j kappa).
  // From kappa = 50 the ratio stays under 1 for j < 100, and the terms fall
  // under 1e-17 after at most 13 of them (long before the series' smallest
  // term, where it would start to diverge).
  double term = 1.0, sum = 0.0;
  for (int j = 1; j < 100; ++j) {
    term *= (2.0 * j - 1) * (2.0 * j - 1) / (8.0 * j * kappa);
    sum += term;
    if (term < 1e-17 * (1.0 + sum)) break;
  }
  return -0.5 * std::log(2 * M_PI * kappa) + std::log1p(sum);
}

void EnergyOptions::check() const {
  // Every field but visibility is an option of the suggest table: checked
  // with its ranges, with every other option at its (valid) default.
  SuggestOptions as_suggest;
  as_suggest.energy = *this;
  check_options(as_suggest, suggest_option_table());
  visibility.check();
}

std::string energy_terms_text(const EnergyTerms& t) {
  std::ostringstream out;
  if (t.whole_mesh)
    out << "refinement " << t.refinement << ", exploration " << t.exploration;
  else
    out << "occlusion " << t.occlusion << ", focus " << t.focus << ", parallax " << t.parallax
        << ", incidence " << t.incidence;
  return out.str();
}

double EnergyOptions::kappa() const {
  const double sigma = incidence_sigma * kDeg;
  return 1.0 / (sigma * sigma);
}

WorstRegion worst_region(const TriangleMesh& mesh, const std::vector<float>& pri, int k,
                         const std::vector<char>* exclude) {
  if (pri.size() != mesh.num_faces())
    throw Error("PRI has " + std::to_string(pri.size()) + " values for " +
                std::to_string(mesh.num_faces()) + " faces");
  if (k < 1) throw Error("the worst set needs K >= 1 faces");
  std::vector<int> candidates;
  for (std::size_t f = 0; f < pri.size(); ++f)
    if (!std::isnan(pri[f]) && !(exclude && (*exclude)[f])) candidates.push_back(int(f));
  if (candidates.empty())
    throw Error("no observed face: PRI is undefined everywhere (fewer than 2 views see each face)");
  const std::size_t n = std::min<std::size_t>(std::size_t(k), candidates.size());
  // Highest PRI first; ties by face id, so the choice is deterministic.
  std::partial_sort(candidates.begin(), candidates.begin() + n, candidates.end(), [&](int a, int b) {
    return pri[a] != pri[b] ? pri[a] > pri[b] : a < b;
  });
  WorstRegion r;
  r.faces.assign(candidates.begin(), candidates.begin() + n);
  std::map<int, Vec3> normal_sum;
  double area_sum = 0;
  Vec3 normal_acc = Vec3::Zero();
  for (int f : r.faces) {
    const Vec3 n_f = mesh.face_normal(f);
    const double area = mesh.face_area(f);
    r.centroid += area * mesh.face_centroid(f);
    normal_acc += area * n_f;
    area_sum += area;
    for (int v : mesh.faces[f]) {
      auto [it, inserted] = normal_sum.try_emplace(v, Vec3::Zero());
      it->second += n_f;
    }
  }
  r.centroid = area_sum > 0 ? Vec3(r.centroid / area_sum) : mesh.face_centroid(r.faces[0]);
  r.mean_normal = normal_acc.norm() > 0 ? Vec3(normal_acc.normalized()) : Vec3::UnitZ();
  for (const auto& [v, sum] : normal_sum) {
    r.vertices.push_back(v);
    r.normals.push_back(sum.norm() > 0 ? Vec3(sum.normalized()) : r.mean_normal);
  }
  return r;
}

double focus_term(const PinholeCamera& camera, const Vec3& vertex, double penalty) {
  Vec2 px;
  if (!camera.project(vertex, &px) || !camera.in_image(px)) return penalty;
  // Image centre in pixel-centre coordinates; sx = W/3, sy = H/3, so the
  // outer image corner scores -2.25.
  const double cx0 = (camera.width - 1) / 2.0, cy0 = (camera.height - 1) / 2.0;
  const double sx = camera.width / 3.0, sy = camera.height / 3.0;
  const double dx = px.x() - cx0, dy = px.y() - cy0;
  return -dx * dx / (2 * sx * sx) - dy * dy / (2 * sy * sy);
}

double incidence_term(double angle, const EnergyOptions& o) {
  const double kappa = o.kappa();
  return von_mises_log_density(angle - o.incidence_mu * kDeg, kappa,
                               std::log(2 * M_PI) + log_bessel_i0_scaled(kappa));
}

double parallax_term(const Vec3& candidate, const Vec3& existing, const Vec3& vertex,
                     const EnergyOptions& o) {
  const double B = (candidate - existing).norm(), H = (candidate - vertex).norm();
  return H > 0 && B / H > o.parallax_delta ? 1.0 : o.penalty;
}

EnergyEvaluator::EnergyEvaluator(const TriangleMesh& mesh, const RayCaster& caster,
                                 const WorstRegion& region, std::vector<Vec3> existing,
                                 const EnergyOptions& options)
    : mesh_(mesh),
      caster_(caster),
      region_(region),
      existing_(std::move(existing)),
      options_(options),
      absolute_eps_(options.visibility.absolute_eps_of_diagonal * mesh.bounding_box().diagonal()),
      incidence_log_norm_scaled_(std::log(2 * M_PI) + log_bessel_i0_scaled(options.kappa())) {
  options_.check();
}

bool EnergyEvaluator::vertex_visible(const PinholeCamera& camera, const Vec3& v) const {
  return point_visible(caster_, camera, v, options_.visibility.relative_eps, absolute_eps_);
}

EnergyTerms EnergyEvaluator::evaluate(const PinholeCamera& P) const {
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  EnergyTerms e;
  const Vec3 c = P.center();
  const double kappa = options_.kappa(), mu = options_.incidence_mu * kDeg;
  const double cos_mu = std::cos(mu), sin_mu = std::sin(mu);
  const auto& w = options_.weights;
  for (std::size_t k = 0; k < region_.vertices.size(); ++k) {
    const Vec3& v = mesh_.vertices[std::size_t(region_.vertices[k])];
    e.occlusion += w[0] * (vertex_visible(P, v) ? 1.0 : options_.penalty);
    e.focus += w[1] * focus_term(P, v, options_.penalty);
    double par = 0;
    for (const Vec3& other : existing_) par += parallax_term(c, other, v, options_);
    e.parallax += w[2] * par;
    // The von Mises log density of the incidence angle theta in closed form,
    // from cos theta (no acos): -2 kappa sin^2((theta - mu) / 2) =
    // kappa (cos theta cos mu + sin theta sin mu - 1), sin theta >= 0 on [0, pi].
    const Vec3 ray = c - v;
    const double len = ray.norm();
    const double cos_t = len > 0 ? std::clamp(region_.normals[k].dot(ray) / len, -1.0, 1.0) : -1.0;
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    e.incidence += w[3] * (kappa * (cos_t * cos_mu + sin_t * sin_mu - 1.0) - incidence_log_norm_scaled_);
  }
  e.total = e.occlusion + e.focus + e.parallax + e.incidence;
  return e;
}

std::vector<int> EnergyEvaluator::seen_faces(const PinholeCamera& P) const {
  std::vector<int> out;
  const Vec3 c = P.center();
  for (int f : region_.faces) {
    bool ok = mesh_.face_normal(std::size_t(f)).dot(c - mesh_.face_centroid(std::size_t(f))) > 0;
    for (int k = 0; k < 3 && ok; ++k) ok = vertex_visible(P, mesh_.vertices[std::size_t(mesh_.faces[f][k])]);
    if (ok) out.push_back(f);
  }
  return out;
}

bool EnergyEvaluator::sees_all_vertices(const PinholeCamera& P) const {
  for (int v : region_.vertices)
    if (!vertex_visible(P, mesh_.vertices[std::size_t(v)])) return false;
  return true;
}

}  // namespace meshnbv
