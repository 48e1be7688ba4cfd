// Middlebury-style evaluation of a reconstructed surface against a
// reference (SPEC section 6; Seitz et al. 2006):
// - accuracy: sample the reconstruction uniformly, take each sample's
//   distance to the reference, report percentiles (80/90/99 %);
// - completeness: sample the reference uniformly, report the share of
//   samples within each threshold of the reconstruction.
// Both sample sets use one spacing (the density is fixed per scene), so
// numbers of different reconstructions of one scene are comparable.
#pragma once

#include <cstdint>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/mesh.h"

namespace meshnbv::eval {

struct EvaluationOptions {
  // Completeness thresholds in scene units (Middlebury's 0.75/1.25/1.75 mm in metres).
  std::vector<double> thresholds = {0.00075, 0.00125, 0.00175};
  std::vector<double> percentiles = {80, 90, 99};  // accuracy percentiles, in (0, 100]
  // Distance between surface samples; 0 = automatic: the reference's
  // bounding-box diagonal / 500.
  double sample_spacing = 0.0;
  std::size_t max_samples = 2000000;  // per surface; the spacing grows to respect it
  std::uint64_t seed = 1;             // of the sampling (results are deterministic)
  int threads = 0;                    // 0 = all cores

  void check() const;  // throws Error for values out of range
};

struct EvaluationResult {
  // (percentile, distance); NaN distances when the reconstruction is empty.
  std::vector<std::pair<double, double>> accuracy;
  // (threshold, share of reference samples within it, in [0, 1]).
  std::vector<std::pair<double, double>> completeness;
  double mean_accuracy = 0;            // mean distance reconstruction -> reference (NaN if empty)
  double sample_spacing = 0;           // the spacing used
  std::size_t reconstruction_samples = 0, reference_samples = 0;
  double reconstruction_area = 0, reference_area = 0;
  double seconds = 0;
};

// Deterministic, area-uniform samples: each face receives
// floor(area / spacing^2 + u) uniform points (u from the seeded generator).
std::vector<Vec3> sample_surface(const TriangleMesh& mesh, double spacing, std::uint64_t seed);

// `reference` must have a non-degenerate face; an empty reconstruction
// gives NaN accuracy and zero completeness.
EvaluationResult evaluate_reconstruction(const TriangleMesh& reconstruction,
                                         const TriangleMesh& reference,
                                         const EvaluationOptions& options = {});

// Linear interpolation between order statistics (numpy's default);
// `values` is reordered. NaN for an empty vector.
double percentile(std::vector<double>& values, double percent);

// The faces of `mesh` whose three vertices are seen from at least
// `min_views` of the cameras (in front, inside the image, unoccluded) and
// that face them: the part of a ground truth that the views can reconstruct.
TriangleMesh observable_part(const TriangleMesh& mesh, const std::vector<PinholeCamera>& cameras,
                             int min_views);

}  // namespace meshnbv::eval
