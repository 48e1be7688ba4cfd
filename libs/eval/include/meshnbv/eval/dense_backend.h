// Dense reconstruction from known poses on the CPU (docs/evaluation.md,
// "Dense backend"): for each selected view, depth maps from stereo pairs
// with its best partners among the selected views (rectified with the known
// poses, OpenCV's semi-global matching), checked against each other
// (geometric consistency: at least `min_agreeing` pairs give the same depth
// within `consistency` pixels of disparity), then fused into points that
// remember the views that saw them, for the visibility mesher.
//
// The disparity range and the partners come from the step's sparse points
// (as COLMAP's own dense stereo takes them from its sparse model). Each
// pair's disparity map is cached on disk by a key of everything it depends
// on (both images, both cameras, the disparity range rounded outwards, the
// matcher's parameters), so a step of the loop computes only the pairs it
// has not seen before.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/eval/visibility_mesher.h"
#include "meshnbv/image.h"
#include "meshnbv/progress.h"
#include "meshnbv/scene.h"

namespace meshnbv::eval {

// What the loop reconstructs with: COLMAP's sparse points, or depth maps
// fused into dense points; either way meshed by the chosen mesher.
enum class BackendKind { Sparse, Dense };
BackendKind parse_backend(const std::string& name);  // sparse | dense
std::string backend_name(BackendKind kind);

struct DenseOptions {
  // Images whose longer side exceeds this are downscaled (area filter)
  // before matching; the depth maps have that size.
  int max_image_size = 800;
  // Stereo partners per view, among the selected views that share at least
  // `min_shared_points` sparse points with it at a median triangulation
  // angle in [min_angle, max_angle] degrees; ranked by shared points times
  // min(1, angle / target_angle)^2.
  int partners = 4;
  int min_shared_points = 10;
  double min_angle = 3.0, max_angle = 60.0, target_angle = 15.0;
  // Semi-global matching (OpenCV StereoSGBM): block size (odd), uniqueness
  // ratio (%), and the smoothness penalties P1 = 8 b^2, P2 = 32 b^2.
  int block_size = 5;
  int uniqueness = 10;
  // Pixels whose block has a grey-level standard deviation below this
  // (0..255) get no depth: without texture the matcher only propagates.
  double min_texture = 2.0;
  // Geometric consistency: a pixel's depth is kept when at least this many
  // of its pairs agree with their median within `consistency` pixels of
  // disparity (1 keeps single-pair depths).
  int min_agreeing = 2;
  double consistency = 1.0;
  // Fusion: every `pixel_step`-th pixel of each depth map becomes a point;
  // points merge on a voxel grid of pixel_step times the median pixel
  // footprint, coarsened until at most `max_points` remain.
  int pixel_step = 2;
  int max_points = 150000;

  void check() const;
};

// A depth map in a view's (downscaled) pixel grid; 0 = no depth.
struct DepthMap {
  int width = 0, height = 0;
  std::vector<float> depth;
  // Per pair: the depth change of one pixel of disparity is z^2 * k.
  double k = 0;
  float at(int x, int y) const { return depth[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// The camera with the same pose and field of view for an image of
// `width` x `height` pixels (principal point and focal lengths scaled).
PinholeCamera resized_camera(const PinholeCamera& camera, int width, int height);

// z-depths of `ref`'s pixels from the stereo pair (`ref`, `other`), both
// cameras sized to their (grey) images, for scene depths in [min_depth,
// max_depth] along `ref`'s axis. Throws Error when the pair cannot be
// rectified (no baseline) or the depth range is empty. `disparity_png`,
// when given, is where the disparity map is read from if it exists, and
// written to if not (a cache entry). `scene_points` (world; at least 10 to
// count), when given, narrow the searched disparities to where they lie.
DepthMap stereo_depth(const PinholeCamera& ref, const Image& ref_image, const PinholeCamera& other,
                      const Image& other_image, double min_depth, double max_depth,
                      const DenseOptions& options, const std::string& disparity_png = {},
                      const std::vector<Vec3>& scene_points = {});

struct DenseStats {
  std::size_t views = 0;            // views with a depth map
  std::size_t pairs = 0;            // stereo pairs used
  std::size_t pairs_computed = 0;   // of those, matched now (the rest from the cache)
  std::size_t depth_pixels = 0;     // consistent depths over all depth maps
  std::size_t contradicted = 0;     // depths dropped: other views saw through them
  std::size_t raw_points = 0;       // points before the voxel merge
  std::size_t points = 0;           // fused points
  double voxel = 0;                 // merge cell size (scene units)
  double seconds_stereo = 0, seconds_fusion = 0;
  std::vector<std::string> failures;  // one line per view or pair that failed
};

// Dense points of the views `selected` (indices into `views`, each with an
// image file); `sparse` are the step's sparse points (SparsePoint::views
// index `views`). Views or pairs that fail are skipped and listed in
// `stats`; no points at all is an empty result, not an error.
std::vector<SparsePoint> dense_points(const std::vector<View>& views, const std::vector<int>& selected,
                                      const std::vector<SparsePoint>& sparse, const std::string& cache_dir,
                                      const DenseOptions& options, DenseStats* stats = nullptr,
                                      const ProgressCallback& progress = {});

}  // namespace meshnbv::eval
