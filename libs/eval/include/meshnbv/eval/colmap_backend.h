// Sparse reconstruction with known poses through Debian's COLMAP 3.8 (CPU;
// command line): SIFT features and matches are computed once per dataset
// and cached; each triangulation uses only the selected images, with their
// poses fixed (`point_triangulator`). See docs/evaluation.md.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "meshnbv/eval/visibility_mesher.h"
#include "meshnbv/progress.h"
#include "meshnbv/scene.h"

namespace meshnbv::eval {

struct ColmapOptions {
  std::string executable = "colmap";
  std::string matcher = "exhaustive";  // exhaustive | sequential (ordered rings: much faster)
  int sequential_overlap = 5;          // sequential matcher: neighbours matched on each side
  int threads = 2;
  int max_image_size = 3200;           // SIFT extraction resizes larger images
  // SIFT's peak threshold: lower finds more features on weak texture
  // (COLMAP's default is 0.0067; 0.004 doubles the matches on the synthetic scenes).
  double peak_threshold = 0.004;
  // Matching guided by the epipolar geometry of the verified pairs (more matches).
  bool guided_matching = true;
  void check() const;
};

// True when `executable help` runs.
bool colmap_available(const std::string& executable = "colmap");

// The triangulated points; SparsePoint::views index the workspace's views.
struct SparseModel {
  std::vector<SparsePoint> points;
  std::vector<double> reprojection_errors;  // pixels, per point
  double seconds = 0;
};

class ColmapWorkspace {
 public:
  // Prepares `cache_dir` for `views` (every one needs an image): links to
  // the images, the database with features and matches. A cache made for
  // the same images, intrinsics and matcher is reused as it is.
  ColmapWorkspace(const std::string& cache_dir, std::vector<View> views,
                  const ColmapOptions& options = {}, const ProgressCallback& progress = {});

  // From here on, additions go to a private copy of the database in
  // `dir` (the shared cache stays as it is).
  void detach(const std::string& dir);
  // Adds a view whose image exists (extracts its features) and matches it
  // with the views `match_with`; returns its index. Needs detach() first.
  int add_view(const View& view, const std::vector<int>& match_with);

  // Points from the views `selected` (indices), poses and intrinsics fixed.
  // Fewer than 2 views give an empty model. `work_dir` receives the
  // models and COLMAP's log.
  SparseModel triangulate(const std::vector<int>& selected, const std::string& work_dir) const;

  const std::vector<View>& views() const { return views_; }
  const std::string& database() const { return database_; }
  bool reused_cache() const { return reused_; }

 private:
  struct Ids {
    long long image = 0, camera = 0;
  };
  void read_ids();
  std::string run(const std::vector<std::string>& args, const std::string& log) const;
  std::string peak_threshold() const;
  std::string guided() const;

  ColmapOptions options_;
  std::vector<View> views_;
  std::vector<std::string> names_;  // image names inside image_dir_
  std::string image_dir_, database_, log_;
  std::map<std::string, Ids> ids_;  // by image name
  bool reused_ = false, detached_ = false;
};

// Writes COLMAP's text model of `views` with their known poses: cameras.txt
// (io::colmap_camera_text: PINHOLE, or the model holding the lens; principal point + 0.5 for COLMAP's
// pixel convention), images.txt (no 2-D points), empty points3D.txt.
// `image_ids`/`camera_ids`/`names` per view.
void write_known_pose_model(const std::vector<View>& views, const std::vector<long long>& image_ids,
                            const std::vector<long long>& camera_ids,
                            const std::vector<std::string>& names, const std::string& folder);

// Reads points3D.txt of a COLMAP text model: position, error and the
// image ids of its track (each image once).
struct ColmapPoint {
  Vec3 position;
  double error = 0;
  std::vector<long long> image_ids;
};
std::vector<ColmapPoint> read_colmap_points(const std::string& points3d_txt);

}  // namespace meshnbv::eval
