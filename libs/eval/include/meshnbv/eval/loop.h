// The paper's experiment (Section 4; SPEC section 6): incremental view
// selection with a real reconstruction backend. Bootstrap with a few views,
// then repeatedly reconstruct (COLMAP sparse points with known poses + the
// visibility mesher), measure accuracy and completeness against a
// reference, and choose the next view with a strategy: the next-best-view
// energy on the PRI of the current reconstruction, or a baseline.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "meshnbv/eval/colmap_backend.h"
#include "meshnbv/eval/dense_backend.h"
#include "meshnbv/eval/metrics.h"
#include "meshnbv/eval/strategies.h"
#include "meshnbv/eval/visibility_mesher.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"
#include "meshnbv/progress.h"
#include "meshnbv/renderer.h"
#include "meshnbv/scene.h"
#include "meshnbv/texture.h"

namespace meshnbv::eval {

// What the loop chooses from, and what it measures against.
struct Dataset {
  std::string path;
  std::vector<View> views;  // calibrated candidate views, each with an image
  bool synthetic = false;
  // Synthetic: the ground truth (face attribute "material") and the texture
  // the loop renders every picture with, so new poses can be photographed.
  TriangleMesh truth;
  std::shared_ptr<const SolidTexture> texture;
  RenderOptions render;
};

// A folder made by `meshnbv synth` (truth.ply + scene.json) is synthetic:
// its views are rendered again into `cache_dir`/render with the loop's own
// texture (a deterministic function of the truth), so that pictures taken
// later at new poses match them. Anything else is read as a scene
// (Middlebury, COLMAP, .mlp, JSON) and its views with images are the candidates.
Dataset load_dataset(const std::string& path, const std::string& cache_dir,
                     const ProgressCallback& progress = {});

enum class MesherKind { Delaunay, Poisson };
MesherKind parse_mesher(const std::string& name);  // delaunay | poisson
std::string mesher_name(MesherKind kind);

struct PoissonOptions {
  int depth = 9;       // octree depth of `colmap poisson_mesher`
  double trim = 5;     // its trimming value
  int neighbours = 12; // normals: PCA over this many nearest points
};

struct LoopOptions {
  Strategy strategy = Strategy::Nbv;
  int bootstrap = 3;                 // views of the first reconstruction
  std::vector<int> bootstrap_views;  // indices; empty = view 0 and its nearest neighbours
  int max_views = 0;                 // stop at this many views; 0 = all candidate views
  std::uint64_t seed = 1;            // random strategy (and the sampled candidates)
  // nbv: Given chooses among the dataset's views; Sampled/Refined take new
  // poses anywhere (synthetic datasets only: the renderer takes the picture).
  CandidateMode nbv_candidates = CandidateMode::Given;
  PriOptions pri;
  SuggestOptions suggest;  // mode and top are set by the loop
  int coverage_min_views = 2;
  ColmapOptions colmap;
  // Sparse points with a larger mean reprojection error (pixels) are not
  // meshed (COLMAP keeps up to 4 px; wrong matches sit mostly above 1 px).
  double max_point_error = 2.0;
  // Sparse: the mesher gets COLMAP's points; Dense: depth maps of the
  // selected views (disparity range and partners from those points) fused
  // into dense points (docs/evaluation.md).
  BackendKind backend = BackendKind::Sparse;
  DenseOptions dense;
  MesherKind mesher = MesherKind::Delaunay;
  VisibilityMesherOptions delaunay;
  PoissonOptions poisson;
  EvaluationOptions evaluation;
  // Empty: Middlebury's (0.00075, 0.00125, 0.00175) for real data, 0.5%,
  // 1% and 2% of the truth's bounding-box diagonal for synthetic scenes.
  std::vector<double> thresholds;
  std::string cache_dir;      // COLMAP features/matches, reference; shared between runs
  std::string out_dir;        // results
  std::string save_meshes = "all";  // all | last | none
  bool keep_work = false;     // keep COLMAP's per-step models
  bool snapshots = false;     // a PNG beside each saved mesh, from two dataset views
  // How the nbv strategy computes PRI (not a user option: meshnbv-mpi
  // distributes it over ranks); empty = compute_pri. Incremental from the
  // previous step either way (`previous` may be null).
  std::function<PriResult(const Scene&, const PriOptions&, const PriPrevious* previous)> pri_engine;
  CandidateScorer candidate_scorer;  // likewise for scoring candidates; empty = here
  // nbv: compute each step's PRI from the previous step's, recomputing only
  // the faces that changed (equal to a full computation); false = every face.
  bool incremental_pri = true;

  void check() const;
};

struct StepRecord {
  int step = 0;                 // 0 = bootstrap
  std::vector<std::string> views;  // labels of all views used so far
  std::string added;            // the view added before this step (empty at step 0)
  bool has_added_camera = false;  // its pose (a new pose's too), in loop.json
  PinholeCamera added_camera;
  std::string chosen_by;        // strategy that chose it ("uniform (fallback)" ...)
  std::size_t points = 0, faces = 0;
  EvaluationResult metrics;
  std::string mesh_file;        // relative to out_dir; empty when not saved
  // Why the reconstruction failed or came out empty (the loop goes on);
  // empty when it did not.
  std::string failure;
  DenseStats dense;             // dense backend: depth maps and fusion
  // reconstruct = sparse (COLMAP) + dense (depth maps, fusion) + mesh.
  double seconds_sparse = 0, seconds_dense = 0, seconds_mesh = 0;
  double seconds_reconstruct = 0, seconds_pri = 0, seconds_choose = 0, seconds_evaluate = 0;
  // nbv: faces whose PRI the step computed (incremental PRI) of pri_faces.
  std::size_t pri_recomputed = 0, pri_faces = 0;
};

struct LoopResult {
  std::string dataset;
  bool synthetic = false;
  std::string reference;        // what the metrics compare with
  std::vector<double> thresholds;
  std::vector<StepRecord> steps;
  double seconds = 0;
};

// Runs the loop; writes `out_dir`/steps.csv, loop.json (rewritten after
// every step) and meshes/. `on_step` (optional) sees each finished step.
LoopResult run_loop(const Dataset& dataset, const LoopOptions& options,
                    const ProgressCallback& progress = {},
                    const std::function<void(const StepRecord&)>& on_step = {});

// Reconstruction of the views `selected` of the workspace: COLMAP points,
// with the dense backend depth maps fused into points (their disparity
// maps cached in `cache_dir`), then the chosen mesher. Also used for the
// all-views reference.
struct Reconstruction {
  SparseModel sparse;
  std::size_t points = 0;   // meshed points (sparse or dense) before the mesher's filters
  DenseStats dense;
  TriangleMesh mesh;
  std::string failure;      // why the mesh is empty, when it is
  double seconds = 0;       // all of it: sparse + dense + mesh
  double seconds_sparse = 0, seconds_dense = 0, seconds_mesh = 0;
};
Reconstruction reconstruct(const ColmapWorkspace& workspace, const std::vector<int>& selected,
                           const std::string& work_dir, const LoopOptions& options,
                           const std::string& cache_dir);

// Poisson surface from the points through `colmap poisson_mesher`, normals
// by PCA over nearest neighbours, oriented towards the cameras that saw
// each point.
TriangleMesh poisson_mesh(const std::vector<SparsePoint>& points, const std::vector<Vec3>& centres,
                          const std::string& work_dir, const std::string& colmap_executable,
                          const PoissonOptions& options);

// A picture of `mesh` from `viewer` (zoomed out by `zoom_out`): grey where a
// face's front is seen, red where its back is (inverted or seen from inside).
Image snapshot(const TriangleMesh& mesh, const PinholeCamera& viewer, double zoom_out = 1.3);

// How steps.csv writes a value (8 significant digits, "nan" when not
// finite) and names a percentile or threshold in its columns
// (accuracy_<label>, completeness_<label>; 6 significant digits).
std::string csv_number(double x);
std::string csv_label(double t);

// The per-step table as CSV (one row per step).
std::string steps_csv(const LoopResult& result);

}  // namespace meshnbv::eval
