// meshnbv loop: the paper's experiment (incremental view selection with a
// real reconstruction backend); meshnbv evaluate: Middlebury-style metrics.
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/eval/experiment.h"
#include "meshnbv/eval/loop.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/options.h"
#include "progress_bar.h"

namespace fs = std::filesystem;

namespace meshnbv::cli {
namespace {

std::vector<double> parse_numbers(const std::string& text, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      const double x = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(x)) throw std::invalid_argument(item);
      out.push_back(x);
    } catch (const std::exception&) {
      throw Error(what + ": '" + item + "' is not a number (expected a comma-separated list)");
    }
  }
  if (out.empty()) throw Error(what + ": expected a comma-separated list of numbers");
  return out;
}

std::string join_metrics(const eval::EvaluationResult& m) {
  std::ostringstream ss;
  ss << std::setprecision(4);
  ss << "accuracy";
  for (const auto& [p, v] : m.accuracy) ss << " " << p << "%=" << v;
  ss << ", completeness";
  for (const auto& [t, v] : m.completeness) ss << " " << t << "=" << 100.0 * v << "%";
  return ss.str();
}

struct LoopArgs {
  std::string dataset, out, cache, strategy = "nbv", mode = "given";
  OptionFlags flags;
  std::string bootstrap_views, thresholds, percentiles = "80,90,99", mesher = "delaunay", backend = "sparse",
                                           labelling = "graphcut", facet_support = "any";
  eval::LoopOptions options;
  int bootstraps = 1;
  bool overwrite = false, quiet = false;
};

// The dataset and how views are chosen from it (the nbv strategy with
// every PRI and suggestion option).
void add_selection_options(CLI::App* cmd, LoopArgs* a) {
  cmd->add_option("dataset", a->dataset,
                  "Calibrated images to choose from (Middlebury folder, COLMAP model, .mlp, "
                  ".json) or a folder made by `meshnbv synth` (ground truth; new poses rendered)")
      ->required();
  cmd->add_option("--out", a->out, "Output folder: steps.csv, loop.json, meshes/, reference.ply")
      ->required();
  cmd->add_option("--strategy", a->strategy, "How the next view is chosen")
      ->check(CLI::IsMember({"nbv", "uniform", "random", "coverage"}))
      ->capture_default_str();
  cmd->add_option("--bootstrap", a->options.bootstrap, "Views of the first reconstruction")
      ->capture_default_str();
  cmd->add_option("--bootstrap-views", a->bootstrap_views,
                  "Their indices, comma-separated (default: view 0 and its nearest neighbours)");
  cmd->add_option("--bootstraps", a->bootstraps,
                  "Run the loop this many times, from starting sets spread over the dataset (each "
                  "centred on the view farthest in direction from the centres so far), into "
                  "<out>/bootstrap_<b>/; <out>/bootstraps.csv holds each metric's mean and 95% "
                  "confidence interval per view count")
      ->capture_default_str();
  cmd->add_option("--view-budget", a->options.max_views,
                  "Stop when the reconstruction has this many views (0 = all)")
      ->capture_default_str();
  cmd->add_option("--cache", a->cache,
                  "Folder for COLMAP's features and matches and the reference, shared by runs on "
                  "the same dataset (default: <out>/cache)");
  cmd->add_option("--nbv-candidates", a->mode,
                  "nbv: where the next view comes from: given (the dataset's views), sampled "
                  "or refined (new poses, rendered; synthetic datasets only)")
      ->check(CLI::IsMember({"given", "sampled", "refined"}))
      ->capture_default_str();
  // nbv: every PRI and suggestion option under its one name (options.h);
  // the suggestion's `candidates` is the loop's --nbv-candidates.
  add_pri_options(cmd, &a->flags, &a->options.pri);
  a->flags.add(cmd, suggest_option_table(), &a->options.suggest, {"candidates"});
  cmd->add_option("--coverage-min-views", a->options.coverage_min_views,
                  "coverage: faces seen by fewer selected views count as uncovered")
      ->capture_default_str();
}

// The dense backend's depth maps and fusion (dense_backend.h).
void add_dense_options(CLI::App* cmd, LoopArgs* a) {
  eval::DenseOptions& d = a->options.dense;
  cmd->add_option("--dense-max-image-size", d.max_image_size,
                  "dense: images with a longer side are downscaled before matching (pixels)")
      ->capture_default_str();
  cmd->add_option("--dense-partners", d.partners, "dense: stereo partners per view")->capture_default_str();
  cmd->add_option("--dense-min-angle", d.min_angle,
                  "dense: smallest median triangulation angle of a partner (degrees)")
      ->capture_default_str();
  cmd->add_option("--dense-max-angle", d.max_angle,
                  "dense: largest median triangulation angle of a partner (degrees)")
      ->capture_default_str();
  cmd->add_option("--dense-block-size", d.block_size, "dense: semi-global matching block size (odd)")
      ->capture_default_str();
  cmd->add_option("--dense-min-texture", d.min_texture,
                  "dense: no depth where the block's grey-level standard deviation is below this (0-255)")
      ->capture_default_str();
  cmd->add_option("--dense-min-agreeing", d.min_agreeing,
                  "dense: pairs that must agree on a pixel's depth (1 = no consistency check)")
      ->capture_default_str();
  cmd->add_option("--dense-consistency", d.consistency,
                  "dense: agreement tolerance, in pixels of disparity")
      ->capture_default_str();
  cmd->add_option("--dense-pixel-step", d.pixel_step, "dense: every n-th pixel of a depth map is a point")
      ->capture_default_str();
  cmd->add_option("--dense-max-points", d.max_points,
                  "dense: fused points handed to the mesher (voxel grid coarsened above)")
      ->capture_default_str();
}

// The reconstruction backend: COLMAP's sparse points (and depth maps), then the mesher.
void add_reconstruction_options(CLI::App* cmd, LoopArgs* a) {
  cmd->add_option("--backend", a->backend,
                  "Points to mesh: sparse (COLMAP's triangulated features) or dense (depth maps of "
                  "the selected views by semi-global matching, fused)")
      ->check(CLI::IsMember({"sparse", "dense"}))
      ->capture_default_str();
  add_dense_options(cmd, a);
  cmd->add_option("--max-point-error", a->options.max_point_error,
                  "Sparse points with a larger reprojection error (pixels) are not meshed")
      ->capture_default_str();
  cmd->add_option("--min-point-views", a->options.delaunay.min_views_per_point,
                  "delaunay: points seen by fewer views are not meshed")
      ->capture_default_str();
  cmd->add_option("--mesher", a->mesher, "Surface from the sparse points")
      ->check(CLI::IsMember({"delaunay", "poisson"}))
      ->capture_default_str();
  cmd->add_option("--labelling", a->labelling, "delaunay: free/occupied tetrahedra by min-cut or vote")
      ->check(CLI::IsMember({"graphcut", "vote"}))
      ->capture_default_str();
  cmd->add_option("--facet-support", a->facet_support,
                  "delaunay: which boundary triangles are output (any: a camera of a corner faces "
                  "it; edges: also each edge's ends share a camera; common: one camera saw all "
                  "three corners; all)")
      ->check(CLI::IsMember({"all", "any", "edges", "common"}))
      ->capture_default_str();
  cmd->add_option("--surface-weight", a->options.delaunay.surface_weight,
                  "delaunay/graphcut: cost of each surface facet (times the median visibility)")
      ->capture_default_str();
  cmd->add_option("--min-component-share", a->options.delaunay.min_component_share,
                  "delaunay: drop pieces smaller than this share of the largest")
      ->capture_default_str();
  cmd->add_option("--poisson-depth", a->options.poisson.depth, "poisson: octree depth")
      ->capture_default_str();
  cmd->add_option("--poisson-trim", a->options.poisson.trim, "poisson: trim value")->capture_default_str();
  cmd->add_option("--matcher", a->options.colmap.matcher,
                  "COLMAP matcher, run once per dataset (sequential suits ordered rings)")
      ->check(CLI::IsMember({"exhaustive", "sequential"}))
      ->capture_default_str();
  cmd->add_option("--sequential-overlap", a->options.colmap.sequential_overlap,
                  "sequential matcher: neighbours matched")
      ->capture_default_str();
  cmd->add_option("--sift-peak-threshold", a->options.colmap.peak_threshold,
                  "COLMAP SIFT peak threshold (lower = more features)")
      ->capture_default_str();
  cmd->add_flag("--guided-matching,!--no-guided-matching", a->options.colmap.guided_matching,
                "COLMAP matching guided by the verified epipolar geometry")
      ->default_str("true");
  cmd->add_option("--colmap-binary", a->options.colmap.executable, "COLMAP executable")
      ->capture_default_str();
}

// The metrics and what is written.
void add_output_options(CLI::App* cmd, LoopArgs* a) {
  cmd->add_option("--thresholds", a->thresholds,
                  "Completeness thresholds in scene units (default: 0.00075,0.00125,0.00175 for "
                  "real data; 0.5%,1%,2% of the truth's diagonal for synthetic scenes)");
  cmd->add_option("--percentiles", a->percentiles, "Accuracy percentiles")->capture_default_str();
  cmd->add_option("--sample-spacing", a->options.evaluation.sample_spacing,
                  "Distance between surface samples of the metrics (0 = reference diagonal / 500)")
      ->capture_default_str();
  cmd->add_option("--save-meshes", a->options.save_meshes, "Reconstructions kept in meshes/")
      ->check(CLI::IsMember({"all", "last", "none"}))
      ->capture_default_str();
  cmd->add_flag("--snapshots", a->options.snapshots,
                "Pictures of the saved meshes and the reference (PNG, from two dataset views; red = "
                "a face seen from behind)");
  cmd->add_flag("--incremental-pri,!--no-incremental-pri", a->options.incremental_pri,
                "nbv: compute each step's PRI only for the faces that changed since the last step")
      ->capture_default_str();
  cmd->add_flag("--keep-work", a->options.keep_work, "Keep COLMAP's per-step models in <out>/work");
  cmd->add_flag("--overwrite", a->overwrite, "Write into an output folder holding results");
  cmd->add_flag("--quiet", a->quiet, "No progress output");
}

// The parsed arguments into a->options, checked.
void finish_loop_options(LoopArgs* a) {
  eval::LoopOptions& o = a->options;
  o.strategy = eval::parse_strategy(a->strategy);
  a->flags.apply();
  o.nbv_candidates = parse_candidate_mode(a->mode);
  o.suggest.threads = o.pri.threads;
  o.seed = o.suggest.sampling.seed;
  o.mesher = eval::parse_mesher(a->mesher);
  o.backend = eval::parse_backend(a->backend);
  o.delaunay.labelling = eval::parse_labelling(a->labelling);
  o.delaunay.facet_support = eval::parse_facet_support(a->facet_support);
  check_option(a->bootstraps >= 1 && a->bootstraps <= 1000, "--bootstraps", "in [1, 1000]", a->bootstraps);
  if (a->bootstraps > 1 && !a->bootstrap_views.empty())
    throw Error("--bootstrap-views names one starting set: it cannot be combined with --bootstraps " +
                std::to_string(a->bootstraps));
  if (!a->bootstrap_views.empty()) {
    o.bootstrap_views.clear();
    for (double x : parse_numbers(a->bootstrap_views, "--bootstrap-views")) {
      if (x != std::floor(x) || x < 0 || x > 1e6)
        throw Error("--bootstrap-views: indices must be whole numbers in [0, 1000000], got '" +
                    a->bootstrap_views + "'");
      o.bootstrap_views.push_back(int(x));
    }
  }
  if (!a->thresholds.empty()) o.thresholds = parse_numbers(a->thresholds, "--thresholds");
  o.evaluation.percentiles = parse_numbers(a->percentiles, "--percentiles");
  o.out_dir = a->out;
  o.cache_dir = a->cache;
  o.pri_engine = [](const Scene& scene, const PriOptions& pri, const PriPrevious* previous) {
    return scene_pri(scene, pri, {}, previous);
  };
  o.candidate_scorer = candidate_scorer();
  o.check();
  o.evaluation.thresholds = o.thresholds.empty() ? o.evaluation.thresholds : o.thresholds;
  o.evaluation.check();
}

void run_loop_command(const LoopArgs& a) {
  const eval::LoopOptions& o = a.options;
  io::check_can_write_folder(a.out);
  if (!a.cache.empty()) io::check_can_write_folder(a.cache);
  std::error_code ec;
  if ((fs::exists(fs::path(a.out) / "loop.json", ec) || fs::exists(fs::path(a.out) / "bootstraps.json", ec)) &&
      !a.overwrite)
    throw Error("output folder holds results of a loop; pass --overwrite to replace them", a.out);
  if (!eval::colmap_available(o.colmap.executable))
    throw Error("COLMAP not found ('" + o.colmap.executable +
                " help' failed): install Debian's colmap package or pass --colmap");
  // Replacing results: what an earlier run left must not mix with the new ones.
  for (const char* sub : {"meshes", "images", "work"}) fs::remove_all(fs::path(a.out) / sub);
  for (const char* file : {"loop.json", "steps.csv", "bootstraps.json", "bootstraps.csv"})
    fs::remove(fs::path(a.out) / file, ec);
  if (fs::is_directory(a.out, ec))
    for (const auto& entry : fs::directory_iterator(a.out))
      if (entry.is_directory() && entry.path().filename().string().rfind("bootstrap_", 0) == 0)
        fs::remove_all(entry.path());
  fs::create_directories(a.out);
  const std::string cache = a.cache.empty() ? (fs::path(a.out) / "cache").string() : a.cache;
  ProgressBar bar(a.quiet);
  const eval::Dataset dataset = eval::load_dataset(a.dataset, cache, bar.callback());
  bar.finish();
  if (!a.quiet)
    std::cout << "dataset: " << dataset.views.size() << " views" << (dataset.synthetic ? " (synthetic)" : "")
              << "; strategy " << a.strategy << "\n";
  ProgressBar loop_bar(true);
  auto print_step = [&](int run, const eval::StepRecord& s) {
    if (run > 0) std::cout << "run " << run << "/" << a.bootstraps << " ";
    std::cout << "step " << s.step << ": " << s.views.size() << " views";
    if (!s.added.empty()) std::cout << " (+" << s.added << ", " << s.chosen_by << ")";
    std::cout << ", " << s.points << " points, " << s.faces << " faces; " << join_metrics(s.metrics);
    if (!s.failure.empty()) std::cout << "; FAILED: " << s.failure;
    std::cout << "; " << std::setprecision(3)
              << s.seconds_reconstruct + s.seconds_pri + s.seconds_choose + s.seconds_evaluate << " s\n"
              << std::flush;
  };
  if (a.bootstraps > 1) {
    const auto sets = eval::spread_bootstraps(dataset.views, a.bootstraps, o.bootstrap);
    if (!a.quiet) {
      std::cout << a.bootstraps << " starting sets:";
      for (const auto& set : sets) {
        std::cout << " {";
        for (std::size_t k = 0; k < set.size(); ++k) std::cout << (k ? "," : "") << set[k];
        std::cout << "}";
      }
      std::cout << "\n";
    }
    const eval::BootstrapRuns runs = eval::run_bootstraps(dataset, o, sets, loop_bar.callback(), print_step);
    double seconds = 0;
    for (const auto& r : runs.runs) seconds += r.seconds;
    std::cout << "reference: " << runs.runs.front().reference << "\n";
    std::cout << "results: " << (fs::path(a.out) / "bootstraps.csv").string() << ", "
              << (fs::path(a.out) / "bootstraps.json").string() << ", "
              << (fs::path(a.out) / "bootstrap_<b>").string() << "/ (" << std::setprecision(4) << seconds
              << " s)\n";
    return;
  }
  const eval::LoopResult r =
      eval::run_loop(dataset, o, loop_bar.callback(), [&](const eval::StepRecord& s) { print_step(0, s); });
  std::cout << "reference: " << r.reference << "\n";
  std::cout << "results: " << (fs::path(a.out) / "steps.csv").string() << ", "
            << (fs::path(a.out) / "loop.json").string() << " (" << std::setprecision(4) << r.seconds
            << " s)\n";
}

struct EvalArgs {
  std::string recon, reference, json, thresholds = "0.00075,0.00125,0.00175", percentiles = "80,90,99";
  eval::EvaluationOptions options;
  bool overwrite = false;
};

nlohmann::json evaluation_json(const EvalArgs& e, const eval::EvaluationResult& r) {
  nlohmann::json j;
  j["format"] = "meshnbv-evaluation";
  j["reconstruction"] = e.recon;
  j["reference"] = e.reference;
  nlohmann::json acc = nlohmann::json::array(), comp = nlohmann::json::array();
  for (const auto& [p, v] : r.accuracy)
    acc.push_back({{"percentile", p}, {"distance", std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr)}});
  for (const auto& [t, v] : r.completeness) comp.push_back({{"threshold", t}, {"share", v}});
  j["accuracy"] = acc;
  j["completeness"] = comp;
  j["mean_accuracy"] = std::isfinite(r.mean_accuracy) ? nlohmann::json(r.mean_accuracy) : nlohmann::json(nullptr);
  j["samples"] = {{"reconstruction", r.reconstruction_samples},
                  {"reference", r.reference_samples},
                  {"spacing", r.sample_spacing}};
  j["area"] = {{"reconstruction", r.reconstruction_area}, {"reference", r.reference_area}};
  return j;
}

// meshnbv evaluate
void add_evaluate_command(CLI::App& app) {
  auto e = std::make_shared<EvalArgs>();
  CLI::App* ev = app.add_subcommand(
      "evaluate", "Middlebury-style accuracy (distance of the reconstruction to the reference at "
                  "percentiles) and completeness (share of the reference within thresholds)");
  ev->add_option("reconstruction", e->recon, "Reconstructed mesh (PLY, OBJ, OFF)")->required();
  ev->add_option("reference", e->reference, "Reference mesh (ground truth)")->required();
  ev->add_option("--thresholds", e->thresholds, "Completeness thresholds in scene units")
      ->capture_default_str();
  ev->add_option("--percentiles", e->percentiles, "Accuracy percentiles")->capture_default_str();
  ev->add_option("--sample-spacing", e->options.sample_spacing,
                 "Distance between surface samples (0 = reference diagonal / 500)")
      ->capture_default_str();
  ev->add_option("--json", e->json, "Results as JSON");
  ev->add_flag("--overwrite", e->overwrite, "Replace an existing JSON file");
  ev->callback([e]() {
    e->options.thresholds = parse_numbers(e->thresholds, "--thresholds");
    e->options.percentiles = parse_numbers(e->percentiles, "--percentiles");
    e->options.check();
    if (!e->json.empty()) io::check_can_write(e->json, e->overwrite);
    const TriangleMesh recon = io::read_mesh(e->recon);
    const TriangleMesh reference = io::read_mesh(e->reference);
    const eval::EvaluationResult r = eval::evaluate_reconstruction(recon, reference, e->options);
    std::cout << join_metrics(r) << "\n"
              << "samples: " << r.reconstruction_samples << " reconstruction, " << r.reference_samples
              << " reference, spacing " << r.sample_spacing << "\n";
    if (!e->json.empty()) {
      const nlohmann::json j = evaluation_json(*e, r);
      io::write_atomically(e->json, [&](std::ostream& out) { out << j.dump(2) << "\n"; }, e->overwrite);
      std::cout << "json: " << e->json << "\n";
    }
  });
}

}  // namespace

void add_loop_command(CLI::App& app) {
  auto a = std::make_shared<LoopArgs>();
  CLI::App* cmd = app.add_subcommand(
      "loop",
      "The paper's experiment: bootstrap with a few views, then repeatedly reconstruct (COLMAP "
      "sparse points with the known poses + a Delaunay visibility mesher), measure accuracy and "
      "completeness, and add the view a strategy chooses");
  add_selection_options(cmd, a.get());
  add_reconstruction_options(cmd, a.get());
  add_output_options(cmd, a.get());
  cmd->callback([a]() {
    finish_loop_options(a.get());
    run_loop_command(*a);
  });
  add_evaluate_command(app);
}

}  // namespace meshnbv::cli
