// The whole-mesh energy (issue #16, beyond the paper; docs/nbv.md): a
// candidate pose is worth the improvement it is expected to bring to the
// reconstructability of the whole mesh, weighted by what the quality index
// says of each face. For a surface point with the views V that see it, the
// reconstructability is the heuristic of Smith, Moehrle, Goesele and
// Heidrich 2018 ("Aerial path planning for urban scene reconstruction";
// ../shared/notes/anchors.md), reimplemented from its description:
//   h(V) = sum over pairs {a, b} of V of g(alpha_ab) min(cos theta_a, cos theta_b) min(s_a, s_b)
//   g(alpha) = (1 - sigmoid(alpha; pi/4, 8)) sigmoid(alpha; pi/16, 32)
// with alpha the angle between the pair's rays at the point, theta a ray's
// incidence angle and s = 1 - d / d_max its distance scale; a view counts
// where the point projects into its image, unoccluded, facing it under less
// than `max_incidence` degrees, nearer than d_max. A point's first view is
// credited half of an ideal pair, g_max cos theta s / 2 (the best such over
// V), so that a view of a point nobody sees yet is worth something; the
// second view then brings the pair itself. Views are added one at a time,
// and a new view's increment (its pairs and credit) is multiplied by
// sigmoid(alpha_min; pi/16, 32), alpha_min its smallest angle to a view
// already there: the heuristic's sum over pairs would count a repeat of
// an existing view as a new one (a twin of a view would gain almost what
// the view did), while such a ray triangulates nothing new.
//
// Optionally a candidate must also be matchable (beyond Smith et al.;
// docs/nbv.md): features match only between views of a point from nearby
// directions, and a view whose rays are far from every existing view's
// gets no point, however many wide pairs the sum gives it. With
// match_angle < 180, a candidate's increment at a cluster that existing
// views see counts only where its ray is within match_angle of one of
// theirs; at a cluster no view sees yet (the first-view credit alone), it
// is multiplied by the candidate's matched share: the area share of the
// surface it sees (projection, facing, distance; no occlusion test, on an
// even subsample of at most 256 clusters) that an existing view sees
// within match_angle of its ray. Batch picks count the same way. Off
// (180) by default: in the paired experiment it helped on templeRing's
// ring and hurt the fortress's new poses (docs/nbv.md).
//
// A face's utility is -(max(T - h, 0))^2 (the target T = gain_target:
// diminishing returns, nothing more once reached), its weight the quality
// index's rank among the observed faces, in (0, 1] (the worst face 1), or
// exploration_weight for a face that is unobserved (PRI undefined) or on
// the mesh's boundary (a hole's border, where the surface goes on
// unreconstructed). A candidate's energy is the weighted utility it adds,
//   E(P) = sum_f area_f w_f [(T - h_f)_+^2 - (T - h_f - dh_f(P))_+^2] / (T^2 A)
// with A the mesh's area: the share of the weighted deficit it removes, in
// [0, 1]. Faces are scored in compact clusters (same place, same facing:
// runs of a Morton curve split by the dominant axis of the normal), each at
// the centroid of its face nearest the cluster's centroid, with the
// cluster's area-weighted mean normal.
//
// Surface not yet reconstructed is not in the mesh, so no view could gain
// by seeing it. With explore_hull, the mesh's convex hull (its vertices
// without the farthest 1% from their median) stands for it: points
// spread over the hull, about half as many as the clusters, farther from
// the mesh than their spacing and seen by no existing view, join the
// clusters (without faces) with exploration_weight, and A becomes the
// mesh's area plus theirs.
#pragma once

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/energy.h"
#include "meshnbv/mesh.h"
#include "meshnbv/raycaster.h"

namespace meshnbv {

// paper: the SPEC's energy over the worst region (energy.h);
// reconstructability: the whole-mesh gain of this header.
enum class EnergyKind { Paper, Reconstructability };
EnergyKind parse_energy_kind(const std::string& name);  // paper | reconstructability
std::string energy_kind_name(EnergyKind kind);

struct GainOptions {
  double target = 1.0;             // T, the reconstructability a face needs (tuned: bench/eval/tune_gain.sh)
  double exploration_weight = 1.0; // weight of unobserved and boundary faces
  int clusters = 2048;             // clusters scored per candidate; 0 = one per face
  double max_incidence = 85.0;     // degrees; a view at more than this does not count (Smith)
  bool explore_hull = true;        // the unseen part of the convex hull stands for missing surface
  double match_angle = 180.0;      // degrees; a ray farther than this from every existing one gains nothing (180 = off)
  VisibilityOptions visibility;    // the occlusion test's (suggest: the energy's)
};

// g(alpha) above, for alpha in radians.
double pair_angle_score(double alpha);

class GainEvaluator {
 public:
  // `pri` per face (NaN = unobserved); `existing` the views already taken.
  // Throws Error when pri does not match the mesh.
  GainEvaluator(const TriangleMesh& mesh, const RayCaster& caster, const std::vector<float>& pri,
                const std::vector<PinholeCamera>& existing, const GainOptions& options);

  // refinement: the gain on observed faces; exploration: on unobserved and
  // boundary ones; total: their sum. The paper's four terms stay 0.
  EnergyTerms evaluate(const PinholeCamera& candidate) const;
  // The clusters the candidate improves, with their weighted gains (summing
  // to evaluate().total), largest first.
  std::vector<std::pair<int, double>> cluster_gains(const PinholeCamera& candidate) const;
  // The faces of the clusters the candidate improves most, in that order,
  // at most `max_faces` (whole clusters, the last one cut).
  std::vector<int> improved_faces(const PinholeCamera& candidate, std::size_t max_faces) const;
  // The candidate becomes an existing view: later evaluations see it
  // (batches with diminishing returns).
  void add_view(const PinholeCamera& camera);

  // Per face: the weighted deficit w_f (max(T - h, 0) / T)^2 of its
  // cluster, what sampled candidates aim at.
  std::vector<float> face_deficits() const;
  // Per face: the reconstructability h of its cluster, and the weight w_f.
  std::vector<float> face_reconstructability() const;
  const std::vector<float>& face_weights() const { return weight_; }

  std::size_t num_clusters() const { return clusters_.size(); }
  const std::vector<int>& cluster_faces(std::size_t c) const { return clusters_[c].faces; }
  double max_distance() const { return d_max_; }
  // Points of the convex hull standing for surface not yet reconstructed
  // (explore_hull), scored as clusters without faces.
  std::size_t num_hull_points() const { return num_proxy_; }
  std::size_t evaluations() const { return evaluations_.load(std::memory_order_relaxed); }

 private:
  struct Ray {
    Vec3 direction;  // unit, from the point to the camera
    double cos_theta, scale;
  };
  struct Cluster {
    std::vector<int> faces;
    Vec3 point, normal;
    double area = 0;  // of its faces (or its hull sample)
    double weight_refine = 0, weight_explore = 0;  // sum of area w / A
    std::vector<Ray> rays;                         // the views that see it
    double h = 0;                                  // pairs + first-view credit
    double best_single = 0;                        // max cos theta s over rays
  };
  // The ray from c.point to a camera at `centre` when the view counts
  // (projection, facing, incidence, distance, occlusion); false otherwise.
  bool view_ray(const Cluster& c, const PinholeCamera& camera, bool check_occlusion, Ray* ray) const;
  double delta(const Cluster& c, const Ray& r) const;
  // delta(), with `gate` under the matchability condition: 0 where c has
  // rays and none is within match_angle of r; times `share` where c has
  // none (cos_match_ < -1, match_angle 180: no condition).
  double matched_delta(const Cluster& c, const Ray& r, double share, bool gate) const;
  // The candidate's matched share (1 when match_angle >= 180).
  double matched_share(const PinholeCamera& candidate) const;
  // f(cluster index, weighted gain) for every cluster the candidate improves.
  template <class F>
  void for_each_gain(const PinholeCamera& candidate, F&& f) const;
  // Adds the hull's unknown points as clusters; returns their area.
  double add_hull_proxy(const std::vector<PinholeCamera>& existing);
  double weighted_gain(const Cluster& c, double dh) const;

  const TriangleMesh& mesh_;
  const RayCaster& caster_;
  GainOptions options_;
  double cos_max_incidence_ = 0, d_max_ = 0, absolute_eps_ = 0, cos_match_ = -1;
  std::vector<float> weight_;
  std::vector<Cluster> clusters_;
  std::vector<int> cluster_of_face_;
  std::size_t num_proxy_ = 0;
  mutable std::atomic<std::size_t> evaluations_{0};
};

}  // namespace meshnbv
