// How well a per-face quality index predicts the true error of a mesh, and
// the geometric predictors an index has to beat (issue #14): the number of
// views, the widest triangulation angle, and the reconstructability
// heuristic of Smith, Moehrle, Goesele and Heidrich 2018 ("Aerial path
// planning for urban scene reconstruction"; ../shared/notes/anchors.md),
// reimplemented from its description.
#pragma once

#include <cstddef>
#include <vector>

#include "meshnbv/pri.h"
#include "meshnbv/scene.h"

namespace meshnbv::eval {

// Agreement of a score (higher = predicted worse) with a true error, over
// the faces given: Spearman's rank correlation; ROC AUC of the worst
// decile by true error against the rest; precision at K: the share of the
// K faces of highest score that lie in that decile.
struct QualityMetrics {
  std::size_t faces = 0, positives = 0;
  double spearman = 0, auc = 0, precision_at_10 = 0, precision_at_100 = 0;
};
QualityMetrics quality_metrics(const std::vector<double>& score, const std::vector<double>& error);

// Share of the k highest scores (ties broken by index) whose item is positive.
double precision_at_k(const std::vector<double>& score, const std::vector<bool>& positive, std::size_t k);

// Per face, from the views that see it (select_pri_views; Smith's rule
// wants max_incidence_angle 85): how many, the largest angle between the
// rays of two of them at the face's centroid (degrees), and the
// reconstructability: the sum over view pairs of matchability x
// triangulation, with alpha the angle between the pair's rays, theta the
// larger of their incidence angles, s = 1 - d / max_distance the smaller of
// their distance scales:
//   matchability = (1 - sigmoid(alpha; pi/4, 8)) cos(theta),
//   triangulation = sigmoid(alpha; pi/16, 32) s,
//   sigmoid(x; x0, k) = 1 / (1 + exp(-k (x - x0))).
// Views farther than max_distance do not count (max_distance <= 0: twice
// the largest camera-to-centroid distance of the face's views).
struct GeometricPredictors {
  std::vector<int> views;
  std::vector<double> max_angle;
  std::vector<double> reconstructability;
};
GeometricPredictors geometric_predictors(const TriangleMesh& mesh, const PriViewSelection& selection,
                                         double max_distance = 0);

}  // namespace meshnbv::eval
