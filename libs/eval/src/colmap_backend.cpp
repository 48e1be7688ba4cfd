// COLMAP 3.8 driven through its command line (Debian's build has no CUDA
// and no CGAL; only the CPU sparse commands are used).
#include "meshnbv/eval/colmap_backend.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::eval {

void ColmapOptions::check() const {
  if (executable.empty()) throw Error("colmap: no executable given");
  if (matcher != "exhaustive" && matcher != "sequential")
    throw Error("colmap: unknown matcher '" + matcher + "' (expected exhaustive or sequential)");
  check_option(sequential_overlap >= 1 && sequential_overlap <= 1000, "colmap sequential_overlap",
               "in [1, 1000]", sequential_overlap);
  check_option(threads >= 1 && threads <= 1024, "colmap threads", "in [1, 1024]", threads);
  check_option(max_image_size >= 100 && max_image_size <= 100000, "colmap max_image_size",
               "in [100, 100000] pixels", max_image_size);
  check_option(peak_threshold > 0 && peak_threshold <= 1, "colmap SIFT peak_threshold", "in (0, 1]",
               peak_threshold);
}

namespace {

constexpr double kPixelOffset = 0.5;  // COLMAP pixel coordinate - ours (docs/conventions.md)

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

std::string last_lines(const std::string& path, std::size_t n) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) lines.push_back(line);
  std::string out;
  for (std::size_t i = lines.size() > n ? lines.size() - n : 0; i < lines.size(); ++i)
    out += (out.empty() ? "" : " | ") + lines[i];
  return out;
}

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128;
}

std::string intrinsics_params(const PinholeCamera& c) {
  std::ostringstream ss;
  ss << std::setprecision(17) << c.fx << "," << c.fy << "," << c.cx + kPixelOffset << ","
     << c.cy + kPixelOffset;
  return ss.str();
}

void write_lines(const std::string& path, const std::vector<std::string>& lines) {
  io::write_atomically(path, [&](std::ostream& out) {
    for (const auto& l : lines) out << l << "\n";
  });
}

}  // namespace

bool colmap_available(const std::string& executable) {
  return shell("QT_QPA_PLATFORM=offscreen " + quote(executable) + " help >/dev/null 2>&1") == 0;
}

std::string ColmapWorkspace::peak_threshold() const {
  std::ostringstream ss;
  ss << std::setprecision(10) << options_.peak_threshold;
  return ss.str();
}

std::string ColmapWorkspace::guided() const { return options_.guided_matching ? "1" : "0"; }

std::string ColmapWorkspace::run(const std::vector<std::string>& args, const std::string& log) const {
  std::string command = "QT_QPA_PLATFORM=offscreen " + quote(options_.executable);
  for (const auto& a : args) command += " " + quote(a);
  {
    std::ofstream l(log, std::ios::app);
    l << "\n$ " << command << "\n";
  }
  const int rc = shell(command + " >>" + quote(log) + " 2>&1");
  if (rc != 0)
    throw Error("colmap " + args.front() + " failed (exit " + std::to_string(rc) +
                "): " + last_lines(log, 3) + " (log: " + log + ")");
  return log;
}

ColmapWorkspace::ColmapWorkspace(const std::string& cache_dir, std::vector<View> views,
                                 const ColmapOptions& options, const ProgressCallback& progress)
    : options_(options), views_(std::move(views)) {
  options_.check();
  if (views_.size() < 2) throw Error("colmap: at least two views are needed");
  fs::create_directories(fs::path(cache_dir) / "images");
  image_dir_ = fs::absolute(fs::path(cache_dir) / "images").lexically_normal().string();
  database_ = fs::absolute(fs::path(cache_dir) / "database.db").lexically_normal().string();
  log_ = fs::absolute(fs::path(cache_dir) / "colmap.log").lexically_normal().string();

  // Unique names: the image's own file name, prefixed with the view index when two clash.
  std::set<std::string> seen;
  std::ostringstream manifest;
  manifest << "meshnbv colmap cache 1\nmatcher " << options_.matcher << " "
           << options_.sequential_overlap << " size " << options_.max_image_size << " peak "
           << options_.peak_threshold << " guided " << options_.guided_matching << "\n";
  for (std::size_t i = 0; i < views_.size(); ++i) {
    const View& v = views_[i];
    if (!v.has_image()) throw Error("colmap: view '" + v.label + "' has no image");
    v.image_file("COLMAP (an external program)");
    if (!fs::exists(v.image_path)) throw Error("colmap: image not found", v.image_path);
    std::string name = fs::path(v.image_path).filename().string();
    if (!seen.insert(name).second) {
      char prefix[32];
      std::snprintf(prefix, sizeof(prefix), "%04zu_", i);
      name = prefix + name;
      seen.insert(name);
    }
    names_.push_back(name);
    manifest << name << " " << fs::absolute(v.image_path).lexically_normal().string() << " "
             << fs::file_size(v.image_path) << " " << intrinsics_params(v.camera) << " "
             << v.camera.width << "x" << v.camera.height << "\n";
  }
  const std::string manifest_path = (fs::path(cache_dir) / "manifest.txt").string();
  if (fs::exists(manifest_path) && fs::exists(database_) &&
      io::read_file(manifest_path) == manifest.str()) {
    reused_ = true;
    read_ids();
    return;
  }
  // A fresh cache.
  fs::remove(manifest_path);
  fs::remove(database_);
  for (const auto& entry : fs::directory_iterator(image_dir_)) fs::remove(entry.path());
  for (std::size_t i = 0; i < views_.size(); ++i)
    fs::create_symlink(fs::absolute(views_[i].image_path).lexically_normal(), fs::path(image_dir_) / names_[i]);
  const std::string list = (fs::path(cache_dir) / "image_list.txt").string();
  write_lines(list, names_);
  const std::string threads = std::to_string(options_.threads);
  report_progress(progress, 0.0, "colmap features");
  run({"feature_extractor", "--database_path", database_, "--image_path", image_dir_,
       "--image_list_path", list, "--ImageReader.camera_model", "PINHOLE",
       "--ImageReader.single_camera", "0", "--ImageReader.camera_params",
       intrinsics_params(views_[0].camera), "--SiftExtraction.use_gpu", "0",
       "--SiftExtraction.num_threads", threads, "--SiftExtraction.max_image_size",
       std::to_string(options_.max_image_size), "--SiftExtraction.peak_threshold",
       peak_threshold()},
      log_);
  report_progress(progress, 0.3, "colmap matches");
  if (options_.matcher == "sequential")
    run({"sequential_matcher", "--database_path", database_, "--SiftMatching.use_gpu", "0",
         "--SiftMatching.num_threads", threads, "--SiftMatching.guided_matching", guided(),
         "--SequentialMatching.overlap",
         std::to_string(options_.sequential_overlap), "--SequentialMatching.loop_detection", "0"},
        log_);
  else
    run({"exhaustive_matcher", "--database_path", database_, "--SiftMatching.use_gpu", "0",
         "--SiftMatching.num_threads", threads, "--SiftMatching.guided_matching", guided()},
        log_);
  read_ids();
  io::write_atomically(manifest_path, [&](std::ostream& out) { out << manifest.str(); });
  report_progress(progress, 1.0, "colmap matches");
}

void ColmapWorkspace::read_ids() {
  // The database is SQLite: read its images table with Python's sqlite3
  // module (python3 is a dependency of the tests anyway), else the sqlite3 tool.
  const std::string out = fs::path(log_).replace_filename("ids.txt").string();
  const std::string script =
      "import sqlite3,sys\n"
      "c=sqlite3.connect('file:'+sys.argv[1]+'?mode=ro',uri=True)\n"
      "for i,k,n in c.execute('select image_id,camera_id,name from images'): print(i,k,n)\n";
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  int rc = shell(python + " -c " + quote(script) + " " + quote(database_) + " >" + quote(out) +
                 " 2>>" + quote(log_));
  if (rc != 0)
    rc = shell("sqlite3 -separator ' ' " + quote(database_) +
               " 'select image_id,camera_id,name from images' >" + quote(out) + " 2>>" + quote(log_));
  if (rc != 0)
    throw Error("colmap: cannot read the image ids of the database (needs python3 or sqlite3)",
                database_);
  ids_.clear();
  std::ifstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    Ids ids;
    std::string name;
    ss >> ids.image >> ids.camera;
    std::getline(ss >> std::ws, name);
    if (!name.empty()) ids_[name] = ids;
  }
  for (const auto& n : names_)
    if (!ids_.count(n))
      throw Error("colmap: image '" + n + "' is missing from the database (see " + log_ + ")",
                  database_);
}

void ColmapWorkspace::detach(const std::string& dir) {
  fs::create_directories(fs::path(dir) / "images");
  const std::string images = fs::absolute(fs::path(dir) / "images").lexically_normal().string();
  for (const auto& entry : fs::directory_iterator(images)) fs::remove(entry.path());
  for (std::size_t i = 0; i < views_.size(); ++i)
    fs::create_symlink(fs::absolute(views_[i].image_path).lexically_normal(), fs::path(images) / names_[i]);
  const std::string db = fs::absolute(fs::path(dir) / "database.db").lexically_normal().string();
  fs::copy_file(database_, db, fs::copy_options::overwrite_existing);
  image_dir_ = images;
  database_ = db;
  log_ = fs::absolute(fs::path(dir) / "colmap.log").lexically_normal().string();
  detached_ = true;
}

int ColmapWorkspace::add_view(const View& view, const std::vector<int>& match_with) {
  if (!detached_) throw Error("colmap: add_view needs a detached workspace");
  if (!view.has_image() || !fs::exists(view.image_file("COLMAP (an external program)")))
    throw Error("colmap: the new view has no image", view.image_path);
  std::string name = fs::path(view.image_path).filename().string();
  for (const auto& n : names_)
    if (n == name) throw Error("colmap: an image named '" + name + "' is already in the workspace");
  fs::create_symlink(fs::absolute(view.image_path).lexically_normal(), fs::path(image_dir_) / name);
  const std::string dir = fs::path(database_).parent_path().string();
  const std::string list = (fs::path(dir) / "new_image.txt").string();
  write_lines(list, {name});
  const std::string threads = std::to_string(options_.threads);
  run({"feature_extractor", "--database_path", database_, "--image_path", image_dir_,
       "--image_list_path", list, "--ImageReader.camera_model", "PINHOLE",
       "--ImageReader.single_camera", "0", "--ImageReader.camera_params",
       intrinsics_params(view.camera), "--SiftExtraction.use_gpu", "0",
       "--SiftExtraction.num_threads", threads, "--SiftExtraction.max_image_size",
       std::to_string(options_.max_image_size), "--SiftExtraction.peak_threshold",
       peak_threshold()},
      log_);
  views_.push_back(view);
  names_.push_back(name);
  if (!match_with.empty()) {
    std::vector<std::string> pairs;
    for (int j : match_with) pairs.push_back(name + " " + names_.at(std::size_t(j)));
    const std::string pairs_file = (fs::path(dir) / "new_pairs.txt").string();
    write_lines(pairs_file, pairs);
    run({"matches_importer", "--database_path", database_, "--match_list_path", pairs_file,
         "--match_type", "pairs", "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads",
         threads, "--SiftMatching.guided_matching", guided()},
        log_);
  }
  read_ids();
  return int(views_.size()) - 1;
}

void write_known_pose_model(const std::vector<View>& views, const std::vector<long long>& image_ids,
                            const std::vector<long long>& camera_ids,
                            const std::vector<std::string>& names, const std::string& folder) {
  fs::create_directories(folder);
  std::ostringstream cams, imgs;
  cams << "# CAMERA_ID MODEL WIDTH HEIGHT PARAMS[] (written by MeshNBV; COLMAP pixel convention)\n";
  imgs << "# IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME\n";
  cams << std::setprecision(17);
  imgs << std::setprecision(17);
  std::set<long long> written;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const PinholeCamera& c = views[i].camera;
    if (written.insert(camera_ids[i]).second) {
      cams << camera_ids[i] << " " << io::colmap_camera_text(c) << "\n";
    }
    Eigen::Quaterniond q(c.R);
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1.0;
    imgs << image_ids[i] << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << " "
         << c.t.x() << " " << c.t.y() << " " << c.t.z() << " " << camera_ids[i] << " " << names[i]
         << "\n\n";
  }
  io::write_atomically((fs::path(folder) / "cameras.txt").string(),
                       [&](std::ostream& out) { out << cams.str(); });
  io::write_atomically((fs::path(folder) / "images.txt").string(),
                       [&](std::ostream& out) { out << imgs.str(); });
  io::write_atomically((fs::path(folder) / "points3D.txt").string(),
                       [&](std::ostream& out) { out << "# no points: triangulated by COLMAP\n"; });
}

std::vector<ColmapPoint> read_colmap_points(const std::string& path) {
  io::TextTokens tokens(io::read_file(path), path);
  std::vector<std::string> t;
  std::vector<ColmapPoint> out;
  while (tokens.next_line(&t)) {
    if (t.empty() || t[0][0] == '#') continue;
    if (t.size() < 8 || (t.size() - 8) % 2 != 0)
      throw Error("expected POINT3D_ID X Y Z R G B ERROR TRACK[] (pairs)", path, tokens.line());
    ColmapPoint p;
    for (int k = 0; k < 3; ++k)
      p.position[k] = io::parse_double(t[std::size_t(1 + k)], path, tokens.line(), "coordinate");
    p.error = io::parse_double(t[7], path, tokens.line(), "error");
    std::set<long long> images;
    for (std::size_t k = 8; k < t.size(); k += 2)
      images.insert(io::parse_int(t[k], path, tokens.line(), "image id"));
    p.image_ids.assign(images.begin(), images.end());
    out.push_back(std::move(p));
  }
  return out;
}

SparseModel ColmapWorkspace::triangulate(const std::vector<int>& selected,
                                         const std::string& work_dir) const {
  const auto start = std::chrono::steady_clock::now();
  SparseModel model;
  std::set<int> unique(selected.begin(), selected.end());
  if (unique.size() < 2) return model;
  fs::create_directories(work_dir);
  const std::string known = (fs::path(work_dir) / "known").string();
  const std::string tri = (fs::path(work_dir) / "triangulated").string();
  const std::string txt = (fs::path(work_dir) / "triangulated_txt").string();
  fs::remove_all(tri);
  fs::remove_all(txt);
  fs::create_directories(tri);
  fs::create_directories(txt);
  std::vector<View> views;
  std::vector<long long> image_ids, camera_ids;
  std::vector<std::string> names;
  std::map<long long, int> view_of_image;
  for (int i : unique) {
    const std::string& name = names_.at(std::size_t(i));
    const Ids& ids = ids_.at(name);
    views.push_back(views_[std::size_t(i)]);
    image_ids.push_back(ids.image);
    camera_ids.push_back(ids.camera);
    names.push_back(name);
    view_of_image[ids.image] = i;
  }
  write_known_pose_model(views, image_ids, camera_ids, names, known);
  const std::string log = fs::absolute(fs::path(work_dir) / "colmap.log").lexically_normal().string();
  try {
    run({"point_triangulator", "--database_path", database_, "--image_path", image_dir_,
         "--input_path", known, "--output_path", tri, "--Mapper.ba_refine_focal_length", "0",
         "--Mapper.ba_refine_principal_point", "0", "--Mapper.ba_refine_extra_params", "0",
         "--Mapper.num_threads", std::to_string(options_.threads)},
        log);
  } catch (const Error&) {
    // COLMAP 3.8 aborts in its final bundle adjustment when there is no
    // point at all (views without matches): that is an empty model.
    std::ifstream in(log);
    std::string line;
    bool any = false;
    while (std::getline(in, line)) {
      const auto k = line.find("=> Triangulated ");
      if (k != std::string::npos && std::atol(line.c_str() + k + 16) > 0) any = true;
    }
    if (any) throw;
    model.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return model;
  }
  run({"model_converter", "--input_path", tri, "--output_path", txt, "--output_type", "TXT"}, log);
  for (const ColmapPoint& p : read_colmap_points((fs::path(txt) / "points3D.txt").string())) {
    SparsePoint sp;
    sp.position = p.position;
    for (long long id : p.image_ids) {
      const auto it = view_of_image.find(id);
      if (it != view_of_image.end()) sp.views.push_back(it->second);
    }
    model.points.push_back(std::move(sp));
    model.reprojection_errors.push_back(p.error);
  }
  model.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return model;
}

}  // namespace meshnbv::eval
