// Middlebury-style accuracy and completeness (SPEC section 6).
#include "meshnbv/eval/metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "meshnbv/error.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/surface_distance.h"
#include "meshnbv/visibility.h"

namespace meshnbv::eval {

void EvaluationOptions::check() const {
  if (thresholds.empty()) throw Error("evaluation: at least one completeness threshold is needed");
  for (double t : thresholds)
    check_option(t > 0 && std::isfinite(t), "evaluation: thresholds", "positive and finite", t);
  if (percentiles.empty()) throw Error("evaluation: at least one accuracy percentile is needed");
  for (double p : percentiles)
    check_option(p > 0 && p <= 100, "evaluation: percentiles", "in (0, 100]", p);
  check_option(sample_spacing >= 0 && std::isfinite(sample_spacing), "evaluation: the sample spacing",
               ">= 0 and finite (0 = automatic)", sample_spacing);
  check_option(max_samples >= 100 && max_samples <= 100000000, "evaluation: max_samples",
               "in [100, 1e8]", double(max_samples));
  check_option(threads >= 0 && threads <= 1024, "evaluation: threads", "in [0, 1024] (0 = all cores)",
               threads);
}

std::vector<Vec3> sample_surface(const TriangleMesh& mesh, double spacing, std::uint64_t seed) {
  if (!(spacing > 0)) throw Error("surface sampling: the spacing must be positive");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double per_area = 1.0 / (spacing * spacing);
  std::vector<Vec3> out;
  out.reserve(std::size_t(mesh.total_area() * per_area * 1.05) + 16);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const double expected = mesh.face_area(f) * per_area;
    const auto n = static_cast<std::size_t>(std::floor(expected + uni(rng)));
    const Vec3& a = mesh.vertices[mesh.faces[f][0]];
    const Vec3& b = mesh.vertices[mesh.faces[f][1]];
    const Vec3& c = mesh.vertices[mesh.faces[f][2]];
    for (std::size_t k = 0; k < n; ++k) {
      double s = uni(rng), t = uni(rng);
      if (s + t > 1.0) {
        s = 1.0 - s;
        t = 1.0 - t;
      }
      out.push_back(a + s * (b - a) + t * (c - a));
    }
  }
  return out;
}

double percentile(std::vector<double>& values, double percent) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double pos = std::clamp(percent, 0.0, 100.0) / 100.0 * double(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  std::nth_element(values.begin(), values.begin() + long(lo), values.end());
  const double vlo = values[lo];
  if (hi == lo) return vlo;
  const double vhi = *std::min_element(values.begin() + long(lo) + 1, values.end());
  return vlo + (pos - double(lo)) * (vhi - vlo);
}

namespace {

bool has_area(const TriangleMesh& mesh) {
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    if (mesh.face_area(f) > 0) return true;
  return false;
}

std::vector<double> distances(const SurfaceDistance& surface, const std::vector<Vec3>& points) {
  std::vector<double> d(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) d[i] = surface.distance(points[i]);
  });
  return d;
}

}  // namespace

EvaluationResult evaluate_reconstruction(const TriangleMesh& reconstruction,
                                         const TriangleMesh& reference,
                                         const EvaluationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.check();
  reference.validate("reference");
  if (!has_area(reference)) throw Error("evaluation: the reference surface has no area");
  EvaluationResult r;
  r.reference_area = reference.total_area();
  const bool recon_empty = reconstruction.empty() || !has_area(reconstruction);
  if (!recon_empty) {
    reconstruction.validate("reconstruction");
    r.reconstruction_area = reconstruction.total_area();
  }
  double spacing = options.sample_spacing > 0 ? options.sample_spacing
                                              : reference.bounding_box().diagonal() / 500.0;
  const double largest_area = std::max(r.reference_area, r.reconstruction_area);
  const double min_spacing = std::sqrt(largest_area / double(options.max_samples));
  spacing = std::max(spacing, min_spacing);
  r.sample_spacing = spacing;

  const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    const std::vector<Vec3> ref_samples = sample_surface(reference, spacing, options.seed);
    r.reference_samples = ref_samples.size();
    if (recon_empty) {
      for (double p : options.percentiles)
        r.accuracy.emplace_back(p, std::numeric_limits<double>::quiet_NaN());
      for (double t : options.thresholds) r.completeness.emplace_back(t, 0.0);
      r.mean_accuracy = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    // Accuracy: reconstruction samples against the reference.
    {
      const SurfaceDistance to_reference(reference);
      std::vector<Vec3> samples = sample_surface(reconstruction, spacing, options.seed + 1);
      // A reconstruction smaller than the spacing still gets its vertices measured.
      if (samples.empty()) samples = reconstruction.vertices;
      r.reconstruction_samples = samples.size();
      std::vector<double> d = distances(to_reference, samples);
      double sum = 0;
      for (double x : d) sum += x;
      r.mean_accuracy = sum / double(d.size());
      for (double p : options.percentiles) r.accuracy.emplace_back(p, percentile(d, p));
    }
    // Completeness: reference samples against the reconstruction.
    {
      const SurfaceDistance to_reconstruction(reconstruction);
      const std::vector<double> d = distances(to_reconstruction, ref_samples);
      for (double t : options.thresholds) {
        const auto within = std::count_if(d.begin(), d.end(), [t](double x) { return x <= t; });
        r.completeness.emplace_back(t, d.empty() ? 0.0 : double(within) / double(d.size()));
      }
    }
  });
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

TriangleMesh observable_part(const TriangleMesh& mesh, const std::vector<PinholeCamera>& cameras,
                             int min_views) {
  mesh.validate();
  const RayCaster caster(mesh);
  const VertexVisibility visibility(mesh, caster, cameras);
  const std::vector<Vec3> normals = mesh.face_normals();
  TriangleMesh out;
  out.vertices = mesh.vertices;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    int seen = 0;
    for (std::size_t v = 0; v < cameras.size() && seen < min_views; ++v)
      if (face_visible(mesh, normals, visibility, f, v, cameras[v].center())) ++seen;
    if (seen >= min_views) out.faces.push_back(mesh.faces[f]);
  }
  return out;
}

}  // namespace meshnbv::eval
