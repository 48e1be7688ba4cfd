// The incremental view-selection loop of the paper's experiment.
#include "meshnbv/eval/loop.h"
#include "meshnbv/eval/experiment.h"
#include "meshnbv/enum_names.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "meshnbv/error.h"
#include "meshnbv/options.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/synth/generators.h"

namespace fs = std::filesystem;

namespace meshnbv::eval {

constexpr detail::EnumTable<MesherKind, 2> kMeshers = {
    {"delaunay", MesherKind::Delaunay},
    {"poisson", MesherKind::Poisson},
};

MesherKind parse_mesher(const std::string& name) {
  return detail::parse_enum(name, kMeshers, "mesher");
}

std::string mesher_name(MesherKind kind) {
  return detail::enum_name(kind, kMeshers);
}

void LoopOptions::check() const {
  check_option(bootstrap >= 2 && bootstrap <= 1000, "loop bootstrap",
               "in [2, 1000] (at least 2 views)", bootstrap);
  if (!bootstrap_views.empty() && int(bootstrap_views.size()) != bootstrap)
    throw Error("loop: " + std::to_string(bootstrap_views.size()) +
                " bootstrap views given for a bootstrap of " + std::to_string(bootstrap));
  for (int v : bootstrap_views)
    check_option(v >= 0, "loop bootstrap view index", ">= 0", v);
  if (max_views != 0 && max_views >= 0 && max_views < bootstrap)
    throw Error("loop: max views (" + std::to_string(max_views) + ") is below the bootstrap (" +
                std::to_string(bootstrap) + ")");
  check_option(max_views == 0 || (max_views >= bootstrap && max_views <= 100000), "loop max_views",
               "0 (all) or in [bootstrap, 100000]", max_views);
  check_option(coverage_min_views >= 1 && coverage_min_views <= 1000, "loop coverage_min_views",
               "in [1, 1000]", coverage_min_views);
  check_option(max_point_error > 0 && max_point_error <= 1000, "loop max_point_error",
               "in (0, 1000] pixels", max_point_error);
  if (save_meshes != "all" && save_meshes != "last" && save_meshes != "none")
    throw Error("loop: save meshes must be all, last or none, got '" + save_meshes + "'");
  if (out_dir.empty()) throw Error("loop: no output folder");
  check_option(poisson.depth >= 4 && poisson.depth <= 14, "poisson depth", "in [4, 14]",
               poisson.depth);
  check_option(poisson.trim >= 0 && poisson.trim <= 100, "poisson trim", "in [0, 100]",
               poisson.trim);
  check_option(poisson.neighbours >= 3 && poisson.neighbours <= 1000, "poisson neighbours",
               "in [3, 1000]", poisson.neighbours);
  for (double t : thresholds)
    check_option(t > 0 && std::isfinite(t), "loop thresholds", "positive and finite", t);
  pri.check();
  suggest.check();
  colmap.check();
  delaunay.check();
  dense.check();
  evaluation.check();
}

namespace {

// As synth/project.cpp: the finest texture period, in pixels at the median
// camera distance (finer detail would alias differently in each view).
constexpr double kBandLimitPixels = 8.0;

std::shared_ptr<const SolidTexture> loop_texture(const TriangleMesh& truth,
                                                 const std::vector<View>& views) {
  std::vector<Material> materials = default_materials();
  const double diag = truth.bounding_box().diagonal();
  // Texture periods are in metres for buildings; a small object gets them
  // scaled to its size, as `meshnbv synth object` does.
  if (diag < 10.0)
    for (auto& m : materials) m.scale *= diag / 20.0;
  std::vector<double> footprint;
  const Vec3 centre = truth.bounding_box().center();
  for (const auto& v : views) footprint.push_back((v.camera.center() - centre).norm() / v.camera.fx);
  std::nth_element(footprint.begin(), footprint.begin() + long(footprint.size() / 2), footprint.end());
  return std::make_shared<SolidTexture>(1, materials, kBandLimitPixels * footprint[footprint.size() / 2]);
}

Image render_view(const Dataset& d, const RayCaster& caster, const PinholeCamera& camera) {
  RenderInputs in{&d.truth, &caster, d.texture.get(), d.truth.face_attribute(synth::kMaterialAttribute)};
  return render(in, camera, d.render);
}

std::string two_digits(int k) {
  char b[16];
  std::snprintf(b, sizeof(b), "%02d", k);
  return b;
}


nlohmann::json step_json(const StepRecord& s) {
  nlohmann::json j;
  j["step"] = s.step;
  j["num_views"] = s.views.size();
  j["views"] = s.views;
  j["added"] = s.added;
  if (s.has_added_camera) {
    const Vec3 c = s.added_camera.center(), f = s.added_camera.forward();
    j["added_camera"] = {{"center", {c.x(), c.y(), c.z()}}, {"forward", {f.x(), f.y(), f.z()}}};
  }
  j["chosen_by"] = s.chosen_by;
  j["points"] = s.points;
  j["faces"] = s.faces;
  nlohmann::json acc = nlohmann::json::object(), comp = nlohmann::json::object();
  for (const auto& [p, v] : s.metrics.accuracy)
    acc[csv_label(p)] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  for (const auto& [t, v] : s.metrics.completeness) comp[csv_label(t)] = v;
  j["accuracy"] = acc;
  j["completeness"] = comp;
  j["mean_accuracy"] = std::isfinite(s.metrics.mean_accuracy) ? nlohmann::json(s.metrics.mean_accuracy)
                                                             : nlohmann::json(nullptr);
  j["samples"] = {{"reconstruction", s.metrics.reconstruction_samples},
                  {"reference", s.metrics.reference_samples},
                  {"spacing", s.metrics.sample_spacing}};
  j["mesh"] = s.mesh_file;
  if (!s.failure.empty()) j["failure"] = s.failure;
  if (s.dense.pairs > 0 || !s.dense.failures.empty())
    j["dense"] = {{"views", s.dense.views},
                  {"pairs", s.dense.pairs},
                  {"pairs_computed", s.dense.pairs_computed},
                  {"depth_pixels", s.dense.depth_pixels},
                  {"contradicted", s.dense.contradicted},
                  {"raw_points", s.dense.raw_points},
                  {"points", s.dense.points},
                  {"voxel", s.dense.voxel},
                  {"seconds_stereo", s.dense.seconds_stereo},
                  {"seconds_fusion", s.dense.seconds_fusion},
                  {"failures", s.dense.failures}};
  j["seconds"] = {{"reconstruct", s.seconds_reconstruct},
                  {"sparse", s.seconds_sparse},
                  {"dense", s.seconds_dense},
                  {"mesh", s.seconds_mesh},
                  {"pri", s.seconds_pri},
                  {"choose", s.seconds_choose},
                  {"evaluate", s.seconds_evaluate}};
  // nbv: the faces of the step's PRI computed again (incremental), of all.
  j["pri_faces"] = {{"recomputed", s.pri_recomputed}, {"total", s.pri_faces}};
  return j;
}

}  // namespace

Dataset load_dataset(const std::string& path, const std::string& cache_dir,
                     const ProgressCallback& progress) {
  Dataset d;
  d.path = path;
  const fs::path folder(path);
  if (fs::is_directory(folder) && fs::exists(folder / "truth.ply") && fs::exists(folder / "scene.json")) {
    d.synthetic = true;
    d.truth = io::read_ply((folder / "truth.ply").string());
    if (!d.truth.face_attribute(synth::kMaterialAttribute))
      d.truth.set_face_attribute(synth::kMaterialAttribute, std::vector<float>(d.truth.num_faces(), 0.0f));
    const Scene scene = io::read_json_scene((folder / "scene.json").string());
    d.texture = loop_texture(d.truth, scene.views);
    const fs::path render_dir = fs::path(cache_dir) / "render";
    // The render cache belongs to one dataset.
    const std::string stamp = fs::absolute(folder).lexically_normal().string() + "\n";
    const fs::path stamp_file = render_dir / "dataset.txt";
    if (fs::exists(stamp_file) && io::read_file(stamp_file.string()) != stamp) fs::remove_all(render_dir);
    fs::create_directories(render_dir);
    io::write_atomically(stamp_file.string(), [&](std::ostream& out) { out << stamp; });
    const RayCaster caster(d.truth);
    for (std::size_t i = 0; i < scene.views.size(); ++i) {
      View v = scene.views[i];
      v.image_path = fs::absolute(render_dir / (v.label + ".png")).lexically_normal().string();
      v.used = true;
      if (!fs::exists(v.image_path)) render_view(d, caster, v.camera).save(v.image_path);
      d.views.push_back(v);
      report_progress(progress, double(i + 1) / double(scene.views.size()), "render");
    }
  } else {
    const Scene scene = io::read_scene(path);
    for (const View& v : scene.views)
      if (v.has_image()) {
        View u = v;
        u.used = true;
        d.views.push_back(u);
      }
  }
  if (d.views.size() < 3)
    throw Error("the dataset has " + std::to_string(d.views.size()) +
                    " calibrated views with images; the loop needs at least 3",
                path);
  return d;
}

TriangleMesh poisson_mesh(const std::vector<SparsePoint>& points, const std::vector<Vec3>& centres,
                          const std::string& work_dir, const std::string& colmap_executable,
                          const PoissonOptions& options) {
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].views.empty() && points[i].position.allFinite()) usable.push_back(i);
  const std::size_t k = std::size_t(options.neighbours);
  if (usable.size() <= k) return {};
  // Normals: PCA over the k nearest points (brute force: sparse models are small).
  std::vector<Vec3> normals(usable.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, usable.size(), 64), [&](const auto& r) {
    std::vector<std::pair<double, std::size_t>> d(usable.size());
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3& p = points[usable[i]].position;
      for (std::size_t j = 0; j < usable.size(); ++j)
        d[j] = {(points[usable[j]].position - p).squaredNorm(), j};
      std::partial_sort(d.begin(), d.begin() + long(k + 1), d.end());
      Vec3 mean = Vec3::Zero();
      for (std::size_t n = 0; n <= k; ++n) mean += points[usable[d[n].second]].position;
      mean /= double(k + 1);
      Mat3 cov = Mat3::Zero();
      for (std::size_t n = 0; n <= k; ++n) {
        const Vec3 q = points[usable[d[n].second]].position - mean;
        cov += q * q.transpose();
      }
      Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
      Vec3 n = eig.eigenvectors().col(0);
      Vec3 towards = Vec3::Zero();
      for (int v : points[usable[i]].views) towards += (centres[std::size_t(v)] - p).normalized();
      if (n.dot(towards) < 0) n = -n;
      normals[i] = n;
    }
  });
  fs::create_directories(work_dir);
  const std::string in = fs::absolute(fs::path(work_dir) / "points_normals.ply").lexically_normal().string();
  const std::string out = fs::absolute(fs::path(work_dir) / "poisson.ply").lexically_normal().string();
  io::write_atomically(in, [&](std::ostream& o) {
    o << "ply\nformat ascii 1.0\nelement vertex " << usable.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
         "property float ny\nproperty float nz\nend_header\n"
      << std::setprecision(9);
    for (std::size_t i = 0; i < usable.size(); ++i) {
      const Vec3& p = points[usable[i]].position;
      o << p.x() << " " << p.y() << " " << p.z() << " " << normals[i].x() << " " << normals[i].y()
        << " " << normals[i].z() << "\n";
    }
  });
  fs::remove(out);
  const std::string log = fs::absolute(fs::path(work_dir) / "poisson.log").lexically_normal().string();
  std::ostringstream cmd;
  cmd << "QT_QPA_PLATFORM=offscreen '" << colmap_executable << "' poisson_mesher --input_path '" << in
      << "' --output_path '" << out << "' --PoissonMeshing.depth " << options.depth
      << " --PoissonMeshing.trim " << options.trim
      << " --PoissonMeshing.color 0 >'" << log << "' 2>&1";  // no colours in the input
  const int rc = std::system(cmd.str().c_str());
  if (rc != 0 || !fs::exists(out)) throw Error("colmap poisson_mesher failed (log: " + log + ")");
  TriangleMesh mesh = io::read_ply(out);
  mesh.face_attributes.clear();
  mesh.face_colors.clear();
  return mesh;
}

Reconstruction reconstruct(const ColmapWorkspace& workspace, const std::vector<int>& selected,
                           const std::string& work_dir, const LoopOptions& options,
                           const std::string& cache_dir) {
  const auto start = std::chrono::steady_clock::now();
  Reconstruction r;
  r.sparse = workspace.triangulate(selected, work_dir);
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  r.seconds_sparse = since(start);
  const auto t_dense = std::chrono::steady_clock::now();
  std::vector<SparsePoint> points;
  for (std::size_t i = 0; i < r.sparse.points.size(); ++i)
    if (r.sparse.reprojection_errors[i] <= options.max_point_error) points.push_back(r.sparse.points[i]);
  if (options.backend == BackendKind::Dense) {
    points = dense_points(workspace.views(), selected, points, (fs::path(cache_dir) / "dense").string(),
                          options.dense, &r.dense);
    if (points.empty()) {
      r.failure = "no dense points";
      if (!r.dense.failures.empty()) r.failure += " (" + r.dense.failures.front() + ")";
    }
  } else if (points.empty()) {
    r.failure = "no sparse points";
  }
  r.points = points.size();
  r.seconds_dense = since(t_dense);
  const auto t_mesh = std::chrono::steady_clock::now();
  std::vector<Vec3> centres;
  for (const View& v : workspace.views()) centres.push_back(v.camera.center());
  if (!points.empty()) {
    if (options.mesher == MesherKind::Delaunay)
      r.mesh = mesh_from_visibility(points, centres, options.delaunay).mesh;
    else
      r.mesh = poisson_mesh(points, centres, work_dir, options.colmap.executable, options.poisson);
    if (r.mesh.empty()) r.failure = "the mesher made no surface from " + std::to_string(points.size()) + " points";
  }
  r.seconds_mesh = since(t_mesh);
  r.seconds = since(start);
  return r;
}

Image snapshot(const TriangleMesh& mesh, const PinholeCamera& viewer, double zoom_out) {
  PinholeCamera cam = viewer;
  cam.fx /= zoom_out;
  cam.fy /= zoom_out;
  if (mesh.empty()) {
    Image blank(cam.width, cam.height, 3);
    std::fill(blank.data(), blank.data() + blank.bytes(), std::uint8_t(255));
    return blank;
  }
  std::vector<Rgb8> colours(mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    colours[f] = mesh.face_normal(f).dot(cam.center() - mesh.face_centroid(f)) >= 0 ? Rgb8{200, 200, 200}
                                                                                      : Rgb8{220, 60, 50};
  const RayCaster caster(mesh);
  RenderInputs in;
  in.mesh = &mesh;
  in.raycaster = &caster;
  in.face_colors = &colours;
  RenderOptions o;
  o.background = Vec3(1, 1, 1);
  o.light_direction = -cam.forward() + 0.5 * cam.down() * -1.0;
  return render(in, cam, o);
}

std::string csv_number(double x) {
  if (!std::isfinite(x)) return "nan";
  std::ostringstream ss;
  ss << std::setprecision(8) << x;
  return ss.str();
}

std::string csv_label(double t) {
  std::ostringstream ss;
  ss << std::setprecision(6) << t;
  return ss.str();
}

std::string steps_csv(const LoopResult& result) {
  std::ostringstream ss;
  ss << "step,num_views,added,chosen_by,points,faces";
  if (!result.steps.empty()) {
    for (const auto& [p, v] : result.steps[0].metrics.accuracy) ss << ",accuracy_" << csv_label(p);
    for (const auto& [t, v] : result.steps[0].metrics.completeness)
      ss << ",completeness_" << csv_label(t);
  }
  ss << ",mean_accuracy,seconds_reconstruct,seconds_pri,seconds_choose,seconds_evaluate\n";
  for (const StepRecord& s : result.steps) {
    ss << s.step << "," << s.views.size() << "," << s.added << "," << s.chosen_by << "," << s.points
       << "," << s.faces;
    for (const auto& [p, v] : s.metrics.accuracy) ss << "," << csv_number(v);
    for (const auto& [t, v] : s.metrics.completeness) ss << "," << csv_number(v);
    ss << "," << csv_number(s.metrics.mean_accuracy) << "," << csv_number(s.seconds_reconstruct) << ","
       << csv_number(s.seconds_pri) << "," << csv_number(s.seconds_choose) << ","
       << csv_number(s.seconds_evaluate) << "\n";
  }
  return ss.str();
}

namespace {

// The reference the steps are measured against.
struct Reference {
  TriangleMesh mesh;
  std::string description;         // LoopResult::reference
  std::vector<double> thresholds;  // of completeness
};

// The cache name of a reconstructed reference: the options it depends on.
std::string reference_key(const LoopOptions& options) {
  std::ostringstream key;
  key << "reference_v2_" << mesher_name(options.mesher) << "_" << options.max_point_error;
  if (options.backend == BackendKind::Dense) {
    const DenseOptions& d = options.dense;
    key << "_dense_" << d.max_image_size << "_" << d.partners << "_" << d.min_shared_points << "_"
        << d.min_angle << "_" << d.max_angle << "_" << d.target_angle << "_" << d.block_size << "_"
        << d.uniqueness << "_" << d.min_texture << "_" << d.min_agreeing << "_" << d.consistency << "_" << d.pixel_step << "_"
        << d.max_points;
  }
  if (options.mesher == MesherKind::Delaunay)
    key << "_" << labelling_name(options.delaunay.labelling) << "_" << options.delaunay.surface_weight
        << "_" << options.delaunay.min_component_share << "_" << options.delaunay.max_spread << "_"
        << options.delaunay.max_isolation << "_" << facet_support_name(options.delaunay.facet_support) << "_"
        << options.delaunay.min_views_per_point;
  else
    key << "_" << options.poisson.depth << "_" << options.poisson.trim;
  return key.str();
}

// Synthetic datasets: the part of the truth that the dataset's views see.
// Others: the reconstruction from all views with the same backend (cached).
Reference loop_reference(const Dataset& dataset, const std::vector<PinholeCamera>& cams,
                         const ColmapWorkspace& ws, const fs::path& cache, const LoopOptions& options,
                         const ProgressCallback& progress) {
  const std::size_t n = cams.size();
  Reference ref;
  if (dataset.synthetic) {
    ref.mesh = observable_part(dataset.truth, cams, 1);
    ref.description = "ground truth (truth.ply), faces seen by at least one of the " +
                      std::to_string(n) + " dataset views";
    ref.thresholds = options.thresholds;
    if (ref.thresholds.empty()) {
      const double diag = dataset.truth.bounding_box().diagonal();
      ref.thresholds = {0.005 * diag, 0.01 * diag, 0.02 * diag};
    }
    return ref;
  }
  const fs::path ref_file = cache / (reference_key(options) + ".ply");
  if (fs::exists(ref_file)) {
    ref.mesh = io::read_ply(ref_file.string());
  } else {
    report_progress(progress, 0.0, "reference");
    std::vector<int> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = int(i);
    ref.mesh = reconstruct(ws, all, (cache / "reference_work").string(), options, cache.string()).mesh;
    if (ref.mesh.empty()) throw Error("the reconstruction from all views is empty: no reference");
    io::write_ply(ref.mesh, ref_file.string());
  }
  ref.description = "reconstruction from all " + std::to_string(n) +
                    " views with the same backend (" + ref_file.string() + ")";
  ref.thresholds = options.thresholds.empty() ? std::vector<double>{0.00075, 0.00125, 0.00175}
                                              : options.thresholds;
  return ref;
}

// View 0 and the view farthest from it: where the snapshots are taken from.
std::array<std::size_t, 2> snapshot_views(const std::vector<PinholeCamera>& cams) {
  std::array<std::size_t, 2> views = {0, 0};
  for (std::size_t i = 1; i < cams.size(); ++i)
    if ((cams[i].center() - cams[0].center()).norm() > (cams[views[1]].center() - cams[0].center()).norm())
      views[1] = i;
  return views;
}

// The views of the reconstruction so far (indices into the workspace's
// views) and the dataset views left to choose from.
struct Selection {
  std::vector<int> selected, remaining;
};

Selection bootstrap_selection(const Dataset& dataset, const LoopOptions& options) {
  const std::size_t n = dataset.views.size();
  Selection sel;
  sel.selected = options.bootstrap_views.empty() ? spread_bootstraps(dataset.views, 1, options.bootstrap)[0]
                                                 : options.bootstrap_views;
  for (int i : sel.selected)
    if (i < 0 || std::size_t(i) >= n)
      throw Error("loop: bootstrap view " + std::to_string(i) + " is not among the " +
                  std::to_string(n) + " views");
  if (std::set<int>(sel.selected.begin(), sel.selected.end()).size() != sel.selected.size())
    throw Error("loop: the bootstrap views repeat");
  for (std::size_t i = 0; i < n; ++i)
    if (std::find(sel.selected.begin(), sel.selected.end(), int(i)) == sel.selected.end())
      sel.remaining.push_back(int(i));
  return sel;
}

// Whether nbv takes new poses, rendered from the truth, instead of the
// dataset's views; throws when the dataset cannot serve the options.
bool continuous_mode(const Dataset& dataset, const LoopOptions& options) {
  const bool continuous =
      options.strategy == Strategy::Nbv && options.nbv_candidates != CandidateMode::Given;
  if (continuous && !dataset.synthetic)
    throw Error("nbv with sampled or refined candidates needs a synthetic dataset (a folder made by "
                "`meshnbv synth`): only there can a picture be taken at a new pose");
  const std::size_t n = dataset.views.size();
  if (std::size_t(options.bootstrap) >= n && !continuous)
    throw Error("loop: the bootstrap (" + std::to_string(options.bootstrap) +
                ") leaves no candidate among " + std::to_string(n) + " views");
  return continuous;
}

// What every step of run_loop reads.
struct LoopContext {
  const Dataset& dataset;
  const LoopOptions& options;
  const fs::path& out;
  ColmapWorkspace& ws;
  bool continuous;        // nbv with new poses, rendered from the truth
  std::size_t max_views;  // the view budget
};

// Reconstruction from the selected views, measured against the reference,
// and saved (with its snapshots) as options.save_meshes says.
StepRecord measure_step(const LoopContext& ctx, int step, const Selection& sel, const Reconstruction& recon,
                        const TriangleMesh& reference, const EvaluationOptions& eo,
                        const std::array<std::size_t, 2>& snapshot_from, bool last) {
  const LoopOptions& options = ctx.options;
  StepRecord rec;
  rec.step = step;
  for (int i : sel.selected) rec.views.push_back(ctx.ws.views()[std::size_t(i)].label);
  rec.seconds_reconstruct = recon.seconds;
  rec.seconds_sparse = recon.seconds_sparse;
  rec.seconds_dense = recon.seconds_dense;
  rec.seconds_mesh = recon.seconds_mesh;
  rec.points = recon.points;
  rec.failure = recon.failure;
  rec.dense = recon.dense;
  rec.faces = recon.mesh.num_faces();
  rec.metrics = evaluate_reconstruction(recon.mesh, reference, eo);
  rec.seconds_evaluate = rec.metrics.seconds;
  if (options.save_meshes == "all" || (options.save_meshes == "last" && last)) {
    rec.mesh_file = "meshes/step_" + two_digits(step) + "_views_" + two_digits(int(sel.selected.size())) + ".ply";
    io::write_ply(recon.mesh, (ctx.out / rec.mesh_file).string());
    if (options.snapshots) {
      const std::string stem = (ctx.out / rec.mesh_file).replace_extension("").string();
      snapshot(recon.mesh, ctx.dataset.views[snapshot_from[0]].camera).save(stem + "_a.png");
      snapshot(recon.mesh, ctx.dataset.views[snapshot_from[1]].camera).save(stem + "_b.png");
    }
  }
  return rec;
}

// loop.json: the run's options and every step so far.
nlohmann::json loop_json(const LoopContext& ctx, const LoopResult& result, const EvaluationOptions& eo) {
  const LoopOptions& options = ctx.options;
  nlohmann::json j;
  j["format"] = "meshnbv-loop";
  j["version"] = 1;
  j["dataset"] = result.dataset;
  j["synthetic"] = result.synthetic;
  j["strategy"] = strategy_name(options.strategy);
  j["options"] = {{"bootstrap", options.bootstrap},
                  {"max_views", ctx.max_views},
                  {"seed", options.seed},
                  {"candidates", candidate_mode_name(options.nbv_candidates)},
                  {"backend", backend_name(options.backend)},
                  {"mesher", mesher_name(options.mesher)},
                  {"labelling", labelling_name(options.delaunay.labelling)},
                  {"surface_weight", options.delaunay.surface_weight},
                  {"facet_support", facet_support_name(options.delaunay.facet_support)},
                  {"min_point_views", options.delaunay.min_views_per_point},
                  {"max_point_error", options.max_point_error},
                  {"incremental_pri", options.incremental_pri},
                  {"matcher", options.colmap.matcher}};
  // nbv: the PRI and suggestion options, each table under its one names.
  j["options"]["pri"] = nlohmann::json::parse(options_json(options.pri, pri_option_table()));
  j["options"]["suggest"] = nlohmann::json::parse(options_json(options.suggest, suggest_option_table()));
  j["reference"] = result.reference;
  j["thresholds"] = result.thresholds;
  j["percentiles"] = eo.percentiles;
  j["steps"] = nlohmann::json::array();
  for (const auto& s : result.steps) j["steps"].push_back(step_json(s));
  j["seconds"] = result.seconds;
  return j;
}

// Results so far, rewritten after every step.
void write_results(const LoopContext& ctx, const LoopResult& result, const EvaluationOptions& eo) {
  const nlohmann::json j = loop_json(ctx, result, eo);
  io::write_atomically((ctx.out / "loop.json").string(), [&](std::ostream& o) { o << j.dump(2) << "\n"; });
  io::write_atomically((ctx.out / "steps.csv").string(), [&](std::ostream& o) { o << steps_csv(result); });
}

// What the strategies keep from step to step.
struct StrategyState {
  Vec3 centre;                          // uniform: where the dataset's cameras converge
  std::mt19937_64 rng;                  // random
  std::shared_ptr<ImageCache> images;   // nbv: the selected views' images, decoded once
  std::unique_ptr<RayCaster> truth;     // nbv with new poses: renders them
  // nbv: the last step's mesh and PRI, so that the next step computes only
  // the faces that changed (incremental PRI, equal to a full computation).
  std::unique_ptr<PriPrevious> previous_pri;
};

// A strategy's choice of the next view.
struct Choice {
  std::string by;               // the strategy, and whether it fell back
  int pick = -1;                // index into Selection::remaining, or none
  bool take_new_pose = false;   // continuous nbv: render new_pose
  PinholeCamera new_pose;
  double seconds_pri = 0;
  std::size_t pri_recomputed = 0, pri_faces = 0;
};

// nbv: PRI of the reconstruction in the selected views, then the best
// suggestion: one of the dataset views left, or (continuous) a new pose.
// Leaves `choice` alone when there is nothing to reason about.
void choose_by_nbv(const LoopContext& ctx, const Selection& sel, const TriangleMesh& mesh,
                   StrategyState& state, Choice* choice) {
  if (mesh.empty()) return;
  Scene scene;
  scene.mesh = mesh;
  scene.images = state.images;
  for (int i : sel.selected) scene.views.push_back(ctx.ws.views()[std::size_t(i)]);
  const auto tp = std::chrono::steady_clock::now();
  const PriPrevious* previous = ctx.options.incremental_pri ? state.previous_pri.get() : nullptr;
  PriResult pri = ctx.options.pri_engine ? ctx.options.pri_engine(scene, ctx.options.pri, previous)
                                         : compute_pri(scene, ctx.options.pri, {}, previous);
  choice->seconds_pri = std::chrono::duration<double>(std::chrono::steady_clock::now() - tp).count();
  choice->pri_recomputed = pri.recomputed;
  choice->pri_faces = pri.pri.size();
  state.previous_pri = std::make_unique<PriPrevious>(PriPrevious{scene.mesh, pri});
  if (pri.observed == 0) return;
  SuggestOptions so = ctx.options.suggest;
  so.top = 1;
  so.mode = ctx.options.nbv_candidates;
  so.threads = ctx.options.pri.threads;
  std::vector<View> given;
  if (!ctx.continuous) {
    if (sel.remaining.empty()) return;
    for (int i : sel.remaining) {
      View v = ctx.ws.views()[std::size_t(i)];
      v.used = false;
      given.push_back(v);
    }
  }
  const SuggestResult s = suggest_views(scene, pri.pri, so, given, {}, ctx.options.candidate_scorer);
  if (s.suggestions.empty()) return;
  if (ctx.continuous) {
    choice->take_new_pose = true;
    choice->new_pose = s.suggestions[0].camera;
  } else {
    for (std::size_t r = 0; r < sel.remaining.size(); ++r)
      if (ctx.ws.views()[std::size_t(sel.remaining[r])].label == s.suggestions[0].source) choice->pick = int(r);
  }
}

Choice choose_next(const LoopContext& ctx, const Selection& sel, const Reconstruction& recon,
                   StrategyState* state) {
  std::vector<PinholeCamera> sel_cams, rem_cams;
  for (int i : sel.selected) sel_cams.push_back(ctx.ws.views()[std::size_t(i)].camera);
  for (int i : sel.remaining) rem_cams.push_back(ctx.ws.views()[std::size_t(i)].camera);
  Choice choice;
  choice.by = strategy_name(ctx.options.strategy);
  switch (ctx.options.strategy) {
    case Strategy::Uniform: choice.pick = pick_uniform(sel_cams, rem_cams, state->centre); break;
    case Strategy::Random: choice.pick = pick_random(sel.remaining.size(), state->rng); break;
    case Strategy::Coverage:
      if (!recon.mesh.empty())
        choice.pick = pick_coverage(recon.mesh, sel_cams, rem_cams, ctx.options.coverage_min_views);
      break;
    case Strategy::Nbv: choose_by_nbv(ctx, sel, recon.mesh, *state, &choice); break;
  }
  if (!choice.take_new_pose && choice.pick < 0 && !sel.remaining.empty()) {
    // No reconstruction (or nothing observed) to reason about yet.
    choice.pick = pick_uniform(sel_cams, rem_cams, state->centre);
    choice.by += " (fallback: uniform)";
  }
  return choice;
}

// Adds the chosen view to the selection (rendering a new pose first) and
// gives its label; false when there was nothing to choose from (continuous
// mode without any dataset view left).
bool add_choice(const LoopContext& ctx, const Choice& choice, int step, const StrategyState& state,
                Selection* sel, std::string* added) {
  if (choice.take_new_pose) {
    View v;
    v.label = "nbv_" + two_digits(step + 1);
    v.camera = choice.new_pose;
    v.image_path = fs::absolute(ctx.out / "images" / (v.label + ".png")).lexically_normal().string();
    render_view(ctx.dataset, *state.truth, choice.new_pose).save(v.image_path);
    sel->selected.push_back(ctx.ws.add_view(v, sel->selected));
    *added = v.label;
    return true;
  }
  if (choice.pick < 0) return false;
  const int chosen = sel->remaining[std::size_t(choice.pick)];
  sel->remaining.erase(sel->remaining.begin() + choice.pick);
  sel->selected.push_back(chosen);
  *added = ctx.ws.views()[std::size_t(chosen)].label;
  return true;
}

}  // namespace

LoopResult run_loop(const Dataset& dataset, const LoopOptions& options,
                    const ProgressCallback& progress,
                    const std::function<void(const StepRecord&)>& on_step) {
  const auto start = std::chrono::steady_clock::now();
  auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  options.check();
  const bool continuous = continuous_mode(dataset, options);
  const std::size_t n = dataset.views.size();
  const fs::path out(options.out_dir);
  const fs::path cache = options.cache_dir.empty() ? out / "cache" : fs::path(options.cache_dir);
  const fs::path work = out / "work";
  fs::create_directories(out / "meshes");
  fs::create_directories(work);

  LoopResult result;
  result.dataset = dataset.path;
  result.synthetic = dataset.synthetic;

  // Features and matches of the dataset's views (cached).
  ColmapWorkspace ws((cache / "colmap").string(), dataset.views, options.colmap, progress);
  if (continuous) ws.detach((work / "colmap").string());

  std::vector<PinholeCamera> dataset_cams;
  for (const View& v : dataset.views) dataset_cams.push_back(v.camera);
  const Reference reference = loop_reference(dataset, dataset_cams, ws, cache, options, progress);
  result.reference = reference.description;
  result.thresholds = reference.thresholds;
  io::write_ply(reference.mesh, (out / "reference.ply").string());
  const std::array<std::size_t, 2> snapshot_from = snapshot_views(dataset_cams);
  if (options.snapshots) {
    snapshot(reference.mesh, dataset_cams[snapshot_from[0]]).save((out / "reference_a.png").string());
    snapshot(reference.mesh, dataset_cams[snapshot_from[1]]).save((out / "reference_b.png").string());
  }
  EvaluationOptions eo = options.evaluation;
  eo.thresholds = result.thresholds;
  eo.threads = options.pri.threads;

  Selection sel = bootstrap_selection(dataset, options);
  const LoopContext ctx{dataset, options, out, ws, continuous,
                        options.max_views > 0 ? std::size_t(options.max_views) : n};
  StrategyState state{convergence_point(dataset_cams), std::mt19937_64(options.seed),
                      std::make_shared<ImageCache>(), nullptr, nullptr};
  if (continuous) {
    state.truth = std::make_unique<RayCaster>(dataset.truth);
    fs::create_directories(out / "images");
  }

  Choice last_choice;  // the choice that added the newest view (none at step 0)
  std::string added;
  bool has_added_camera = false;
  PinholeCamera added_camera;  // a copy: add_view may move the views
  double seconds_choose = 0;
  for (int step = 0;; ++step) {
    report_progress(progress, double(sel.selected.size()) / double(ctx.max_views), "loop");
    const std::string step_dir = (work / ("step_" + two_digits(step))).string();
    const Reconstruction recon = reconstruct(ws, sel.selected, step_dir, options, cache.string());
    if (!options.keep_work) fs::remove_all(step_dir);
    const bool last = sel.selected.size() >= ctx.max_views || (!continuous && sel.remaining.empty());
    StepRecord rec = measure_step(ctx, step, sel, recon, reference.mesh, eo, snapshot_from, last);
    rec.added = added;
    rec.has_added_camera = has_added_camera;
    rec.added_camera = added_camera;
    rec.chosen_by = last_choice.by;
    rec.seconds_pri = last_choice.seconds_pri;
    rec.pri_recomputed = last_choice.pri_recomputed;
    rec.pri_faces = last_choice.pri_faces;
    rec.seconds_choose = seconds_choose;
    result.steps.push_back(rec);
    result.seconds = seconds_since(start);
    write_results(ctx, result, eo);
    if (on_step) on_step(rec);
    if (last) break;

    const auto t0 = std::chrono::steady_clock::now();
    last_choice = choose_next(ctx, sel, recon, &state);
    if (!add_choice(ctx, last_choice, step, state, &sel, &added)) break;
    added_camera = ws.views()[std::size_t(sel.selected.back())].camera;
    has_added_camera = true;
    seconds_choose = seconds_since(t0) - last_choice.seconds_pri;
  }
  if (!options.keep_work) fs::remove_all(work);
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace meshnbv::eval
