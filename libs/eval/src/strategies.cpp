// Baseline view-selection strategies of the incremental loop.
#include "meshnbv/eval/strategies.h"
#include "meshnbv/enum_names.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/visibility.h"

namespace meshnbv::eval {

constexpr detail::EnumTable<Strategy, 4> kStrategies = {
    {"nbv", Strategy::Nbv},
    {"uniform", Strategy::Uniform},
    {"random", Strategy::Random},
    {"coverage", Strategy::Coverage},
};

Strategy parse_strategy(const std::string& name) {
  return detail::parse_enum(name, kStrategies, "strategy");
}

std::string strategy_name(Strategy strategy) {
  return detail::enum_name(strategy, kStrategies);
}

Vec3 convergence_point(const std::vector<PinholeCamera>& cameras) {
  if (cameras.empty()) return Vec3::Zero();
  // Sum over axes of (I - d d^T) (x - c) = 0.
  Mat3 A = Mat3::Zero();
  Vec3 b = Vec3::Zero();
  Vec3 mean = Vec3::Zero();
  for (const auto& cam : cameras) {
    const Vec3 d = cam.forward().normalized();
    const Mat3 P = Mat3::Identity() - d * d.transpose();
    A += P;
    b += P * cam.center();
    mean += cam.center();
  }
  mean /= double(cameras.size());
  Eigen::JacobiSVD<Mat3> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const auto& s = svd.singularValues();
  if (s(2) < 1e-6 * std::max(s(0), 1e-300)) return mean;
  return svd.solve(b);
}

int pick_uniform(const std::vector<PinholeCamera>& selected,
                 const std::vector<PinholeCamera>& candidates, const Vec3& centre) {
  if (candidates.empty()) return -1;
  auto direction = [&](const PinholeCamera& c) {
    const Vec3 d = c.center() - centre;
    const double n = d.norm();
    return n > 0 ? Vec3(d / n) : Vec3(-c.forward());
  };
  std::vector<Vec3> chosen;
  for (const auto& c : selected) chosen.push_back(direction(c));
  int best = -1;
  double best_angle = -1;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Vec3 d = direction(candidates[i]);
    double nearest = M_PI;
    for (const Vec3& s : chosen) nearest = std::min(nearest, std::acos(std::clamp(d.dot(s), -1.0, 1.0)));
    if (nearest > best_angle + 1e-12) {
      best_angle = nearest;
      best = int(i);
    }
  }
  return best;
}

int pick_coverage(const TriangleMesh& mesh, const std::vector<PinholeCamera>& selected,
                  const std::vector<PinholeCamera>& candidates, int min_views,
                  std::vector<int>* counts) {
  if (candidates.empty()) return -1;
  if (counts) counts->assign(candidates.size(), 0);
  if (mesh.empty()) return 0;
  std::vector<PinholeCamera> all = selected;
  all.insert(all.end(), candidates.begin(), candidates.end());
  const RayCaster caster(mesh);
  const VertexVisibility visibility(mesh, caster, all);
  const std::vector<Vec3> normals = mesh.face_normals();
  std::vector<int> gain(candidates.size(), 0);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    int seen = 0;
    for (std::size_t v = 0; v < selected.size(); ++v)
      if (face_visible(mesh, normals, visibility, f, v, all[v].center())) ++seen;
    if (seen >= min_views) continue;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const std::size_t v = selected.size() + c;
      if (face_visible(mesh, normals, visibility, f, v, all[v].center())) ++gain[c];
    }
  }
  if (counts) *counts = gain;
  return int(std::max_element(gain.begin(), gain.end()) - gain.begin());
}

int pick_random(std::size_t count, std::mt19937_64& rng) {
  if (count == 0) return -1;
  std::uniform_int_distribution<std::size_t> pick(0, count - 1);
  return int(pick(rng));
}

}  // namespace meshnbv::eval
