#include "meshnbv/eval/quality.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "meshnbv/error.h"
#include "meshnbv/eval/ranking.h"

namespace meshnbv::eval {

double precision_at_k(const std::vector<double>& score, const std::vector<bool>& positive, std::size_t k) {
  if (score.size() != positive.size()) throw Error("precision_at_k: score and positive differ in length");
  k = std::min(k, score.size());
  if (k == 0) return std::nan("");
  std::vector<std::size_t> order(score.size());
  std::iota(order.begin(), order.end(), 0);
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(k), order.end(),
                    [&](std::size_t a, std::size_t b) { return score[a] != score[b] ? score[a] > score[b] : a < b; });
  std::size_t hits = 0;
  for (std::size_t i = 0; i < k; ++i) hits += positive[order[i]] ? 1 : 0;
  return double(hits) / double(k);
}

QualityMetrics quality_metrics(const std::vector<double>& score, const std::vector<double>& error) {
  if (score.size() != error.size()) throw Error("quality_metrics: score and error differ in length");
  QualityMetrics m;
  m.faces = score.size();
  if (score.size() < 2) return m;
  // The worst decile: the ceil(n / 10) largest errors (ties at the border included).
  std::vector<double> sorted = error;
  const std::size_t k = (sorted.size() + 9) / 10;
  std::nth_element(sorted.begin(), sorted.end() - std::ptrdiff_t(k), sorted.end());
  const double border = *(sorted.end() - std::ptrdiff_t(k));
  std::vector<bool> positive(error.size());
  for (std::size_t i = 0; i < error.size(); ++i) positive[i] = error[i] >= border && error[i] > 0;
  m.positives = std::size_t(std::count(positive.begin(), positive.end(), true));
  m.spearman = spearman(score, error);
  m.auc = roc_auc(score, positive);
  m.precision_at_10 = precision_at_k(score, positive, 10);
  m.precision_at_100 = precision_at_k(score, positive, 100);
  return m;
}

namespace {
double sigmoid(double x, double x0, double k) { return 1.0 / (1.0 + std::exp(-k * (x - x0))); }
}  // namespace

GeometricPredictors geometric_predictors(const TriangleMesh& mesh, const PriViewSelection& selection,
                                         double max_distance) {
  const std::size_t F = mesh.num_faces();
  if (selection.faces.size() != F) throw Error("geometric_predictors: the selection is for another mesh");
  GeometricPredictors g;
  g.views.assign(F, 0);
  g.max_angle.assign(F, 0.0);
  g.reconstructability.assign(F, 0.0);
  std::vector<Vec3> centres;
  for (const auto& c : selection.cameras) centres.push_back(c.center());
  std::vector<Vec3> rays;
  std::vector<double> dist;
  for (std::size_t f = 0; f < F; ++f) {
    const Vec3 c = mesh.face_centroid(f);
    const Vec3 n = mesh.face_normal(f);
    rays.clear();
    dist.clear();
    double far = 0;
    for (int v : selection.faces[f].views) far = std::max(far, (centres[std::size_t(v)] - c).norm());
    const double dmax = max_distance > 0 ? max_distance : 2 * far;
    for (int v : selection.faces[f].views) {
      const Vec3 d = centres[std::size_t(v)] - c;
      if (d.norm() >= dmax) continue;
      rays.push_back(d.normalized());
      dist.push_back(d.norm());
    }
    g.views[f] = int(rays.size());
    for (std::size_t a = 0; a < rays.size(); ++a)
      for (std::size_t b = a + 1; b < rays.size(); ++b) {
        const double alpha = std::acos(std::clamp(rays[a].dot(rays[b]), -1.0, 1.0));
        const double theta = std::max(std::acos(std::clamp(rays[a].dot(n), -1.0, 1.0)),
                                      std::acos(std::clamp(rays[b].dot(n), -1.0, 1.0)));
        const double s = std::min(1 - dist[a] / dmax, 1 - dist[b] / dmax);
        const double match = (1 - sigmoid(alpha, M_PI / 4, 8)) * std::cos(theta);
        const double tri = sigmoid(alpha, M_PI / 16, 32) * s;
        g.reconstructability[f] += match * tri;
        g.max_angle[f] = std::max(g.max_angle[f], alpha * 180.0 / M_PI);
      }
  }
  return g;
}

}  // namespace meshnbv::eval
