// Candidate camera poses for the next view (SPEC section 5): hemisphere
// sampling around the worst region, the safety rules, and a derivative-free
// refinement (the paper's future work).
#pragma once

#include <functional>

#include <cstdint>
#include <vector>

#include "meshnbv/energy.h"
#include "meshnbv/raycaster.h"

namespace meshnbv {

// A pose is safe when it is outside the mesh's volume and at least
// `distance` from its surface.
class SafetyChecker {
 public:
  SafetyChecker(const TriangleMesh& mesh, const RayCaster& caster, double distance);
  // Inside when, along a majority of three fixed directions, the surface
  // crossings of the ray winds around the point: faces seen from their back
  // (leaving a solid) outnumber those seen from their front (entering one).
  // That is the winding number along the ray: right for unions of closed
  // components, disjoint or overlapping, and under an open ground plane
  // (tests/core/test_candidates.cpp). On the surface the answer is
  // unspecified (safe() rejects it as too close).
  bool inside_volume(const Vec3& p) const;
  double distance_to_surface(const Vec3& p) const { return caster_.closest_point(p); }
  bool too_close(const Vec3& p) const { return distance_to_surface(p) < distance_; }
  // Optional ground: points lower than `height` along the unit `up` are
  // below it, and not safe.
  void set_ground(const Vec3& up, double height);
  bool below_ground(const Vec3& p) const { return has_ground_ && up_.dot(p) < ground_; }
  bool safe(const Vec3& p) const { return !below_ground(p) && !too_close(p) && !inside_volume(p); }
  double distance() const { return distance_; }

 private:
  const TriangleMesh& mesh_;
  const RayCaster& caster_;
  double distance_;
  double step_;  // how far past a hit the next one is looked for
  bool has_ground_ = false;
  Vec3 up_ = Vec3::UnitZ();
  double ground_ = 0;
};

// The mesh's lowest height along the unit `up`, robustly: the 1st
// percentile of its vertices' heights (a stray vertex below does not
// count). Throws Error for a mesh without vertices.
double ground_height(const TriangleMesh& mesh, const Vec3& up);

struct SamplingOptions {
  int directions = 512;                               // Fibonacci spiral on the hemisphere
  std::vector<double> distance_factors = {0.75, 1.0, 1.5};  // times the median viewing distance
  std::uint64_t seed = 1;                             // rotates the spiral

  // Throws Error for values out of range: directions and seed by the
  // suggest option table (options.h), and check_not_in_table().
  void check() const;
  // The fields no option table holds: 1 to 16 distance factors, each in
  // (0, 100].
  void check_not_in_table() const;
};

struct CandidateSet {
  std::vector<PinholeCamera> cameras;
  std::size_t generated = 0, rejected_inside = 0, rejected_too_close = 0, rejected_below_ground = 0;
};

// Median distance from the existing cameras to the surface along their
// optical axes (to `fallback_target` when the axis misses the mesh).
double median_viewing_distance(const std::vector<PinholeCamera>& cameras, const RayCaster& caster,
                               const Vec3& fallback_target);
// Mean image-up vector of the cameras (world), normalised; +z if undefined.
Vec3 mean_up(const std::vector<PinholeCamera>& cameras);
// The world's up as the cameras show it: photographs are taken level (no
// roll), so every camera's right axis is horizontal and the up direction
// is the one perpendicular to all of them (the least eigenvector of the
// sum of r r^T), signed as mean_up. Cameras that look down or up tilt
// mean_up; this does not. When the right axes are (nearly) parallel, as
// for one camera, it is mean_up made perpendicular to their mean.
Vec3 level_up(const std::vector<PinholeCamera>& cameras);
// The most common intrinsics (fx, fy, cx, cy, size; no distortion).
PinholeCamera most_common_intrinsics(const std::vector<PinholeCamera>& cameras);

// Cameras on the hemisphere of `region.mean_normal` around `region.centroid`,
// looking at the centroid, with `up` and `intrinsics`; unsafe ones rejected
// and counted.
CandidateSet sample_candidates(const WorstRegion& region, const PinholeCamera& intrinsics,
                               const Vec3& up, double viewing_distance,
                               const SafetyChecker& safety, const SamplingOptions& options);

// A camera at `centre` looking along `direction` with `up` (falls back to
// another up when they are parallel).
PinholeCamera camera_looking(const PinholeCamera& intrinsics, const Vec3& centre,
                             const Vec3& direction, const Vec3& up);

struct RefineOptions {
  int iterations = 150;          // Nelder-Mead iterations
  double position_step = 0.1;    // initial simplex, times the distance to the region
  double angle_step = 5.0;       // initial simplex, degrees

  // Throws Error for values out of range: iterations by the suggest option
  // table (refine_iterations, options.h), and check_not_in_table().
  void check() const;
  // The fields no option table holds: position_step in (0, 10], angle_step
  // in (0, 90].
  void check_not_in_table() const;
};

// Nelder-Mead over position (3) and viewing direction (2); unsafe poses are
// infeasible (not evaluated), so from a safe start it returns a safe pose
// whose energy is >= the start's (the start itself when nothing better was
// found). `evaluations`, when
// given, receives the number of energy evaluations it made.
PinholeCamera refine_candidate(const PinholeCamera& start, const Vec3& up,
                               const EnergyEvaluator& energy, const SafetyChecker& safety,
                               const RefineOptions& options = {},
                               std::size_t* evaluations = nullptr);
// The same for any energy to maximise; the initial simplex's position step
// is relative to the distance from the start to `target`.
PinholeCamera refine_candidate(const PinholeCamera& start, const Vec3& up,
                               const std::function<double(const PinholeCamera&)>& energy,
                               const Vec3& target, const SafetyChecker& safety,
                               const RefineOptions& options = {}, std::size_t* evaluations = nullptr);

}  // namespace meshnbv
