// The next-best-view energy of Morreale, Romanoni, Matteucci, "Predicting
// the Next Best View for 3D Mesh Refinement" (2018), as ../shared/SPEC.md
// section 4 fixes it: for a candidate pose P and each vertex v of the worst
// region,
//   NBV(P, v) = mu1 O(P,v) + mu2 F(P,v) + mu3 sum_c Par(P,c,v) + mu4 I(P,v)
// and E(P) = sum_v NBV(P, v); the next best view maximises E.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/mesh.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/visibility.h"

namespace meshnbv {

struct EnergyOptions {
  // mu1..mu4: occlusion, focus, parallax, incidence.
  std::array<double, 4> weights = {0.6, 1.6, 2.1, 0.6};
  double penalty = -10.0;             // Kp
  double parallax_delta = 0.33;       // B/H threshold
  double incidence_mu = 55.0;         // degrees
  double incidence_sigma = 15.0;      // degrees; kappa = 1 / sigma^2 (radians)
  VisibilityOptions visibility;

  void check() const;  // throws Error for non-finite or out-of-range values
  double kappa() const;
};

// The K worst observed faces and their vertices (SPEC section 4).
struct WorstRegion {
  std::vector<int> faces;      // highest PRI first
  std::vector<int> vertices;   // distinct, ascending
  std::vector<Vec3> normals;   // per vertex: normalised mean of its worst faces' normals
  Vec3 centroid = Vec3::Zero();     // area-weighted centroid of the faces
  Vec3 mean_normal = Vec3::Zero();  // area-weighted mean normal, normalised
};

// `pri` per face (NaN = unobserved); faces flagged in `exclude` are skipped.
// Throws Error when no face has a defined PRI.
WorstRegion worst_region(const TriangleMesh& mesh, const std::vector<float>& pri, int k,
                         const std::vector<char>* exclude = nullptr);

// log(I0(kappa)) - kappa for kappa >= 0: the logarithm of the exponentially
// scaled modified Bessel function of the first kind, order 0, which the
// incidence term's normalisation log(2 pi I0(kappa)) needs. I0 itself
// overflows a double from kappa ~ 713 (incidence_sigma under ~2.15
// degrees). Below kBesselI0AsymptoticFrom it is log(std::cyl_bessel_i(0,
// kappa)) - kappa; from there on the asymptotic series
//   log I0(k) = k - log(2 pi k) / 2 + log1p(1/(8k) + 9/(128k^2) + ...),
// whose terms ((2j-1)!!)^2 / (j! (8k)^j) are summed until they fall under
// 1e-17. At kappa = 50 the two agree to 2e-16 relative (the series alone
// is already within 4e-16 of a long double reference from kappa = 15).
constexpr double kBesselI0AsymptoticFrom = 50.0;
double log_bessel_i0_scaled(double kappa);

// The four terms for one vertex, unweighted (SPEC section 4). The incidence
// term is the von Mises log-density kappa cos(x - mu) - log(2 pi I0(kappa)),
// evaluated as -2 kappa sin^2((x - mu) / 2) - log(2 pi) - log_bessel_i0_scaled
// so that it stays finite for any sigma > 0.
double focus_term(const PinholeCamera& camera, const Vec3& vertex, double penalty);
double incidence_term(double angle_radians, const EnergyOptions& options);
double parallax_term(const Vec3& candidate_centre, const Vec3& existing_centre, const Vec3& vertex,
                     const EnergyOptions& options);

// Weighted contributions summed over the region's vertices; total = their
// sum. The whole-mesh energy (gain.h) fills refinement and exploration
// instead, and total = their sum; each energy leaves the other's terms 0.
struct EnergyTerms {
  double occlusion = 0, focus = 0, parallax = 0, incidence = 0;
  double total = 0;
  double refinement = 0, exploration = 0;  // filled by the whole-mesh energy
  bool whole_mesh = false;  // filled by the whole-mesh energy
};
// "occlusion 1.2, focus -0.3, parallax 5.1, incidence 0.2" (paper) or
// "refinement 0.012, exploration 0.004" (whole mesh), for one-line reports.
std::string energy_terms_text(const EnergyTerms& terms);

class EnergyEvaluator {
 public:
  // `existing` = the centres of the views already used (for parallax).
  EnergyEvaluator(const TriangleMesh& mesh, const RayCaster& caster, const WorstRegion& region,
                  std::vector<Vec3> existing, const EnergyOptions& options);

  EnergyTerms evaluate(const PinholeCamera& candidate) const;
  // Calls of evaluate() so far (thread-safe; for counting the work of
  // callers such as refine_candidate).
  std::size_t evaluations() const { return evaluations_.load(std::memory_order_relaxed); }
  // Worst faces the candidate sees (three vertices visible, facing it).
  std::vector<int> seen_faces(const PinholeCamera& candidate) const;
  // Whether every worst vertex is visible from the candidate.
  bool sees_all_vertices(const PinholeCamera& candidate) const;

  const WorstRegion& region() const { return region_; }
  const std::vector<Vec3>& existing() const { return existing_; }

 private:
  bool vertex_visible(const PinholeCamera& camera, const Vec3& v) const;

  const TriangleMesh& mesh_;
  const RayCaster& caster_;
  WorstRegion region_;
  std::vector<Vec3> existing_;
  EnergyOptions options_;
  double absolute_eps_;
  double incidence_log_norm_scaled_;  // log(2 pi I0(kappa)) - kappa
  mutable std::atomic<std::size_t> evaluations_{0};
};

}  // namespace meshnbv
