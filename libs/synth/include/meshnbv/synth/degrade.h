// Degraded reconstructions of a ground-truth mesh, so that the poorly
// reconstructed regions are known, and the per-face ground-truth error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/mesh.h"

namespace meshnbv::synth {

enum class DegradationKind { Noise, Dent, Bump, Hole, Decimate, Field };

struct Degradation {
  DegradationKind kind = DegradationKind::Noise;
  // Noise: Gaussian sigma; Dent/Bump: peak displacement along the normal;
  // both as a fraction of the bounding-box diagonal. Hole: unused.
  // Decimate: fraction of faces removed (0.9 keeps 10%).
  // Field: peak of a smooth displacement over the whole mesh (a sum of
  // Gaussian bumps of random sign and size, scaled so that its largest
  // magnitude is the strength) plus Gaussian noise of a quarter of it;
  // `radius` is the bumps' mean standard deviation and `center` is unused.
  double strength = 0.01;
  // Region (all but Decimate): a ball around `center` of `radius` (fraction
  // of the diagonal, in (0, 10]). When `center` is not finite, a surface
  // point is drawn from the seed. Strength: at most 1 (Noise, Dent, Bump).
  Vec3 center = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  double radius = 0.15;
};

// "noise", "dent", "bump", "hole", "decimate"; optional ":strength" and
// ":radius" suffixes, e.g. "noise:0.01:0.2". Throws Error on bad text.
Degradation parse_degradation(const std::string& text);
std::string degradation_name(DegradationKind kind);

struct DegradeResult {
  TriangleMesh mesh;                 // the degraded mesh
  std::vector<Vec3> region_centers;  // where each regional degradation went
};

// Applies the degradations in order; deterministic from `seed`.
DegradeResult degrade(const TriangleMesh& truth, const std::vector<Degradation>& degradations,
                      std::uint64_t seed);

// Per-face error of `mesh` against the true surface: the mean distance of
// face samples (barycentric lattice with `samples_per_side` subdivisions) to
// the nearest point of `truth` (CGAL AABB tree).
std::vector<float> face_distance_to_surface(const TriangleMesh& mesh, const TriangleMesh& truth,
                                            int samples_per_side = 3);

}  // namespace meshnbv::synth
