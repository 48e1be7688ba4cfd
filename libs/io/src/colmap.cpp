// COLMAP models, text (cameras.txt, images.txt, points3D.txt, as written by
// `colmap model_converter --output_type TXT`) and binary (colmap_binary.cpp),
// COLMAP 3.x.
//
// Conventions, and how they map to ours:
// - images hold the world-to-camera pose: quaternion (QW QX QY QZ) of R
//   and T with x_cam = R X + T, camera along +z, y down: ours unchanged.
// - COLMAP puts the centre of the top-left pixel at (0.5, 0.5); ours is at
//   (0, 0), so cx_ours = cx_colmap - 0.5 (same for cy, and for the 2-D
//   points), and + 0.5 on write.
// - camera models: colmap_cameras.cpp.
#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "colmap_cameras.h"
#include "colmap_model.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

using colmap::kPixelOffset;

// ---------------------------------------------------------------- reading

std::vector<std::string> split_whitespace(std::string_view line) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.emplace_back(line.substr(start, i - start));
  }
  return tokens;
}

bool is_skippable(const std::vector<std::string>& tokens) {
  return tokens.empty() || tokens[0][0] == '#';
}

// Raw lines, blank ones included: in images.txt an empty line is data (an
// image without 2-D points), so TextTokens (which skips blanks) cannot be used.
class LineCursor {
 public:
  explicit LineCursor(const std::string& text) : text_(text) {}
  bool next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    *line = std::string_view(text_).substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  long number() const { return number_; }

 private:
  const std::string& text_;
  std::size_t pos_ = 0;
  long number_ = 0;
};

int parse_size(const std::string& token, const std::string& file, long line, const char* what) {
  const long long value = parse_int(token, file, line, what);
  if (value <= 0 || value > (1 << 30))
    throw Error(std::string(what) + " must be a positive image size, got " + token, file, line);
  return static_cast<int>(value);
}

colmap::Camera parse_camera_line(const std::vector<std::string>& tokens, const std::string& file,
                                 long line) {
  if (tokens.size() < 4)
    throw Error("expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS..., got " +
                    std::to_string(tokens.size()) + " fields",
                file, line);
  const colmap::CameraModelSpec* spec = colmap::find_model(tokens[1]);
  if (!spec)
    throw Error("unknown camera model '" + tokens[1] + "' (COLMAP 3.8 models: " +
                    colmap::model_names() + ")",
                file, line);
  if (tokens.size() != 4 + spec->num_params)
    throw Error("camera model " + tokens[1] + " takes " + std::to_string(spec->num_params) +
                    " parameters (" + spec->params + "), got " + std::to_string(tokens.size() - 4),
                file, line);
  std::vector<double> params;
  for (std::size_t i = 0; i < spec->num_params; ++i)
    params.push_back(
        parse_double(tokens[4 + i], file, line, "camera parameter " + std::to_string(i + 1)));
  colmap::Camera cam;
  cam.model = spec->name;
  cam.line = line;
  try {
    cam.intrinsics = colmap::camera_from_params(*spec, params);
    cam.intrinsics.width = parse_size(tokens[2], file, line, "WIDTH");
    cam.intrinsics.height = parse_size(tokens[3], file, line, "HEIGHT");
    cam.intrinsics.check("camera " + tokens[0] + " (" + spec->name + ")");
  } catch (const Error& e) {
    throw Error(e.reason(), file, line);
  }
  return cam;
}

std::map<long long, colmap::Camera> read_cameras_txt(const std::string& file) {
  TextTokens text(read_file(file), file);
  std::map<long long, colmap::Camera> cameras;
  std::vector<std::string> tokens;
  while (text.next_line(&tokens)) {
    if (is_skippable(tokens)) continue;
    const long line = text.line();
    const long long id = parse_int(tokens[0], file, line, "CAMERA_ID");
    colmap::Camera cam = parse_camera_line(tokens, file, line);
    auto [it, inserted] = cameras.emplace(id, cam);
    if (!inserted)
      throw Error("camera " + tokens[0] + " is defined twice (also on line " +
                      std::to_string(it->second.line) + ")",
                  file, line);
  }
  if (cameras.empty()) throw Error("no camera defined", file);
  return cameras;
}

Mat3 rotation_from_quaternion(double w, double x, double y, double z, const std::string& file,
                              long line) {
  Eigen::Quaterniond q(w, x, y, z);
  // Written quaternions carry rounding (or are typed by hand): normalise.
  if (!(q.norm() > 1e-12)) throw Error("zero quaternion (QW QX QY QZ all 0)", file, line);
  q.normalize();
  return q.toRotationMatrix();
}

colmap::Image parse_image_line(const std::vector<std::string>& tokens, const std::string& file,
                               long line) {
  // COLMAP reads NAME up to the next space, so names cannot hold spaces.
  if (tokens.size() != 10)
    throw Error(
        "expected 10 fields (IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME; NAME "
        "without spaces), got " +
            std::to_string(tokens.size()),
        file, line);
  const char* names[] = {"QW", "QX", "QY", "QZ", "TX", "TY", "TZ"};
  double v[7];
  for (int i = 0; i < 7; ++i) v[i] = parse_double(tokens[1 + i], file, line, names[i]);
  colmap::Image image;
  image.id = parse_int(tokens[0], file, line, "IMAGE_ID");
  image.R = rotation_from_quaternion(v[0], v[1], v[2], v[3], file, line);
  image.t = Vec3(v[4], v[5], v[6]);
  image.camera_id = parse_int(tokens[8], file, line, "CAMERA_ID");
  image.name = tokens[9];
  image.line = line;
  return image;
}

// The POINTS2D line holds (X, Y, POINT3D_ID) triples, or nothing. A wrong
// field count means the file does not alternate image and points lines
// (e.g. points lines left out).
void parse_points_line(std::string_view text, colmap::Image* image, const std::string& file,
                       long line) {
  const std::vector<std::string> tokens = split_whitespace(text);
  if (!tokens.empty() && tokens[0][0] == '#')
    throw Error("expected the POINTS2D line of image " + std::to_string(image->id) +
                    " (an empty line when it has none), got a comment",
                file, line);
  if (tokens.size() % 3 != 0)
    throw Error("expected the POINTS2D line of image " + std::to_string(image->id) +
                    " (X Y POINT3D_ID triples, or an empty line), got " +
                    std::to_string(tokens.size()) +
                    " fields; every image takes two lines in images.txt",
                file, line);
  image->points2d.reserve(tokens.size() / 3);
  for (std::size_t i = 0; i < tokens.size(); i += 3)
    image->points2d.emplace_back(parse_double(tokens[i], file, line, "POINTS2D X"),
                                 parse_double(tokens[i + 1], file, line, "POINTS2D Y"));
}

std::vector<colmap::Image> read_images_txt(const std::string& file) {
  const std::string text = read_file(file);
  LineCursor cursor(text);
  std::vector<colmap::Image> images;
  std::string_view raw;
  while (cursor.next(&raw)) {
    const std::vector<std::string> tokens = split_whitespace(raw);
    if (is_skippable(tokens)) continue;
    images.push_back(parse_image_line(tokens, file, cursor.number()));
    // The points line follows at once; at the end of the file it may be absent.
    if (cursor.next(&raw)) parse_points_line(raw, &images.back(), file, cursor.number());
  }
  if (images.empty()) throw Error("no image listed", file);
  return images;
}

// POINT3D_ID X Y Z R G B ERROR TRACK[] as (IMAGE_ID, POINT2D_IDX).
std::vector<colmap::Point> read_points_txt(const std::string& file) {
  TextTokens text(read_file(file), file);
  std::vector<colmap::Point> points;
  std::vector<std::string> tokens;
  while (text.next_line(&tokens)) {
    if (is_skippable(tokens)) continue;
    const long line = text.line();
    if (tokens.size() < 8 || (tokens.size() - 8) % 2 != 0)
      throw Error("expected POINT3D_ID X Y Z R G B ERROR then (IMAGE_ID POINT2D_IDX) pairs, got " +
                      std::to_string(tokens.size()) + " fields",
                  file, line);
    colmap::Point p;
    for (int k = 0; k < 3; ++k) p.position(k) = parse_double(tokens[1 + k], file, line, "X Y Z");
    for (std::size_t i = 8; i < tokens.size(); i += 2)
      p.track.emplace_back(parse_int(tokens[i], file, line, "IMAGE_ID"),
                           parse_int(tokens[i + 1], file, line, "POINT2D_IDX"));
    points.push_back(std::move(p));
  }
  return points;
}

// Where images may live, in the order read_colmap tries them (scene_io.h).
std::vector<fs::path> image_folder_candidates(const fs::path& model, const std::string& image_dir) {
  std::vector<fs::path> candidates;
  if (!image_dir.empty())
    candidates.push_back(image_dir);
  else
    candidates = {model / "images", model / ".." / "images", model / ".." / ".." / "images", model};
  for (auto& c : candidates) c = fs::absolute(c).lexically_normal();
  return candidates;
}

// The first candidate holding the first image; empty if none does.
fs::path find_image_folder(const std::vector<fs::path>& candidates,
                           const std::string& first_image) {
  for (const auto& c : candidates)
    if (is_file(resolve(first_image, c.string()))) return c;
  return {};
}

// The folder every image name is resolved against; when no candidate holds
// the first image, the last one, with a warning.
std::string choose_image_folder(const fs::path& model, const std::string& image_dir,
                                const std::string& first_image, Scene* scene) {
  const std::vector<fs::path> candidates = image_folder_candidates(model, image_dir);
  const fs::path found = find_image_folder(candidates, first_image);
  if (!found.empty()) return found.string();
  std::string looked;
  for (const auto& c : candidates) looked += (looked.empty() ? "" : ", ") + c.string();
  scene->warnings.push_back("images not found: '" + first_image + "' is in none of " + looked +
                            "; image paths are resolved against " + candidates.back().string() +
                            " (pass the image folder to use)");
  return candidates.back().string();
}

// COLMAP's dense workspace keeps its mesh beside (or one level above) the model.
void attach_mesh(const fs::path& model, Scene* scene) {
  const fs::path candidates[] = {model / "meshed.ply", model / ".." / "meshed-poisson.ply",
                                 model / ".." / "meshed-delaunay.ply"};
  for (const auto& c : candidates) {
    if (!is_file(c)) continue;
    scene->mesh_path = c.lexically_normal().string();
    scene->mesh = read_mesh(scene->mesh_path);
    return;
  }
}

bool is_binary_model(const fs::path& folder) {
  return is_file(folder / "cameras.bin") && is_file(folder / "images.bin");
}

fs::path model_folder(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("no such folder", path);
  fs::path folder(path);
  // Accept the model's files themselves as well as their folder.
  if (!fs::is_directory(folder, ec)) folder = folder.parent_path();
  if (folder.empty()) folder = ".";
  if (is_binary_model(folder)) return folder;
  for (const char* name : {"cameras.txt", "images.txt"})
    if (!is_file(folder / name))
      throw Error(std::string("not a COLMAP model: ") + name +
                      " missing (and no cameras.bin + images.bin)",
                  folder.string());
  return folder;
}

// Text model; as COLMAP itself, the binary one wins when a folder holds both.
colmap::Model read_model(const fs::path& folder) {
  if (is_binary_model(folder)) return colmap::read_binary_model(folder.string());
  colmap::Model model;
  model.cameras_file = (folder / "cameras.txt").string();
  model.images_file = (folder / "images.txt").string();
  model.points_file = (folder / "points3D.txt").string();
  model.cameras = read_cameras_txt(model.cameras_file);
  model.images = read_images_txt(model.images_file);
  model.has_points = is_file(model.points_file);
  if (model.has_points) model.points = read_points_txt(model.points_file);
  return model;
}

void sort_images(colmap::Model* model) {
  auto& images = model->images;
  std::sort(images.begin(), images.end(),
            [](const colmap::Image& a, const colmap::Image& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < images.size(); ++i)
    if (images[i].id == images[i - 1].id)
      throw Error("IMAGE_ID " + std::to_string(images[i].id) + " appears twice", model->images_file,
                  std::max(images[i].line, images[i - 1].line));
}

// The sparse points with their observations as (view, pixel) in our
// convention; track entries naming no image or 2-D point are counted.
void attach_sparse_points(const colmap::Model& model, Scene* scene) {
  std::map<long long, int> view_of;
  for (std::size_t i = 0; i < model.images.size(); ++i) view_of[model.images[i].id] = int(i);
  std::size_t dangling = 0;
  scene->sparse_points.reserve(model.points.size());
  for (const colmap::Point& p : model.points) {
    SparsePoint sp;
    sp.position = p.position;
    for (const auto& [image_id, idx] : p.track) {
      const auto it = view_of.find(image_id);
      const auto& points2d = it == view_of.end() ? std::vector<Vec2>() : model.images[std::size_t(it->second)].points2d;
      if (it == view_of.end() || idx < 0 || std::size_t(idx) >= points2d.size()) {
        ++dangling;
        continue;
      }
      sp.observations.emplace_back(it->second, points2d[std::size_t(idx)] - Vec2(kPixelOffset, kPixelOffset));
    }
    scene->sparse_points.push_back(std::move(sp));
  }
  if (dangling)
    scene->warnings.push_back(std::to_string(dangling) + " track entries of " + model.points_file +
                              " name an image or 2-D point the model does not hold; ignored");
}

// ---------------------------------------------------------------- writing

using IntrinsicsKey = std::pair<std::string, std::vector<double>>;

IntrinsicsKey intrinsics_key(const PinholeCamera& c) {
  std::vector<double> params;
  const colmap::CameraModelSpec& spec = colmap::model_for(c, &params);
  params.push_back(c.width);
  params.push_back(c.height);
  return {spec.name, params};
}

std::string camera_line(int id, const PinholeCamera& c) {
  return std::to_string(id) + ' ' + colmap_camera_text(c);
}

// Whether a relative_to() result stays inside its base folder.
bool is_under(const std::string& relative) {
  const fs::path p(relative);
  return !p.empty() && !p.is_absolute() && *p.begin() != "..";
}

fs::path absolute_normal(const std::string& path) { return fs::absolute(path).lexically_normal(); }

// NAME of every view: its image path relative to `base`, or (base empty)
// absolute; a view without image keeps its label, since COLMAP needs a name.
std::vector<std::string> names_relative_to(const Scene& scene, const fs::path& base) {
  std::vector<std::string> names;
  for (const View& v : scene.views) {
    if (!v.has_image())
      names.push_back(v.label);
    else
      names.push_back(base.empty() ? absolute_normal(v.image_path).string()
                                   : relative_to(v.image_path, base.string()));
  }
  return names;
}

// Whether read_colmap, which resolves every name against the first image
// folder candidate holding the first image, finds each view's image again.
bool names_resolve_back(const Scene& scene, const std::vector<std::string>& names,
                        const fs::path& model) {
  const auto candidates = image_folder_candidates(model, {});
  fs::path folder = find_image_folder(candidates, names.front());
  if (folder.empty()) folder = candidates.back();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (scene.views[i].has_image() && absolute_normal(resolve(names[i], folder.string())) !=
                                          absolute_normal(scene.views[i].image_path))
      return false;
  return true;
}

// Clean names relative to the first candidate image folder holding every
// image; else relative to the model folder; else absolute paths, whichever
// read_colmap resolves back to the same files.
std::vector<std::string> choose_image_names(const Scene& scene, const fs::path& model) {
  if (scene.views.empty()) return {};
  auto candidates = image_folder_candidates(model, {});
  const fs::path model_itself = candidates.back();
  candidates.pop_back();
  for (const fs::path& base : candidates) {
    const bool holds_all = std::all_of(scene.views.begin(), scene.views.end(), [&](const View& v) {
      return !v.has_image() || is_under(relative_to(v.image_path, base.string()));
    });
    if (!holds_all) continue;
    auto names = names_relative_to(scene, base);
    if (names_resolve_back(scene, names, model)) return names;
  }
  auto names = names_relative_to(scene, model_itself);
  if (names_resolve_back(scene, names, model)) return names;
  return names_relative_to(scene, {});
}

std::string image_line(int id, int camera_id, const PinholeCamera& c, const std::string& name) {
  Eigen::Quaterniond q(c.R);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;  // COLMAP's habit: QW >= 0
  std::ostringstream out;
  out << std::setprecision(17) << id << ' ' << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
      << ' ' << c.t.x() << ' ' << c.t.y() << ' ' << c.t.z() << ' ' << camera_id << ' ' << name;
  return out.str();
}

struct ColmapModelText {
  std::vector<std::string> cameras;  // one line each
  std::vector<std::string> images;   // the image line of each (points line empty)
};

ColmapModelText build_model_text(const Scene& scene, const fs::path& folder) {
  ColmapModelText text;
  std::map<IntrinsicsKey, int> camera_ids;
  std::set<std::string> names;
  const std::vector<std::string> chosen = choose_image_names(scene, folder);
  for (std::size_t i = 0; i < scene.views.size(); ++i) {
    const View& view = scene.views[i];
    const std::string what = "view " + std::to_string(i) + " ('" + view.label + "')";
    view.camera.check(what);
    const std::string& name = chosen[i];
    if (name.empty() || std::any_of(name.begin(), name.end(),
                                    [](unsigned char ch) { return std::isspace(ch) != 0; }))
      throw Error(what + ": COLMAP image names must be non-empty and without spaces, got '" + name +
                  "'");
    if (!names.insert(name).second)
      throw Error(what + ": image name '" + name + "' is used twice; COLMAP needs unique names");
    IntrinsicsKey key;
    try {
      key = intrinsics_key(view.camera);
    } catch (const Error& e) {
      throw Error(what + ": " + e.reason());
    }
    auto [it, added] = camera_ids.emplace(key, static_cast<int>(camera_ids.size()) + 1);
    if (added) text.cameras.push_back(camera_line(it->second, view.camera));
    text.images.push_back(image_line(static_cast<int>(i) + 1, it->second, view.camera, name));
  }
  return text;
}

void write_cameras_txt(std::ostream& out, const ColmapModelText& text) {
  out << "# Camera list with one line of data per camera:\n"
      << "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
      << "# Number of cameras: " << text.cameras.size() << "\n";
  for (const auto& line : text.cameras) out << line << '\n';
}

void write_images_txt(std::ostream& out, const ColmapModelText& text) {
  out << "# Image list with two lines of data per image:\n"
      << "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
      << "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
      << "# Number of images: " << text.images.size() << ", mean observations per image: 0\n";
  for (const auto& line : text.images) out << line << "\n\n";  // empty POINTS2D line
}

void write_points3d_txt(std::ostream& out) {
  out << "# 3D point list with one line of data per point:\n"
      << "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
      << "# Number of points: 0, mean track length: 0\n";
}

}  // namespace

std::string colmap_camera_text(const PinholeCamera& c) {
  std::vector<double> params;
  const colmap::CameraModelSpec& spec = colmap::model_for(c, &params);
  std::ostringstream out;
  out << std::setprecision(17) << spec.name << ' ' << c.width << ' ' << c.height;
  for (double p : params) out << ' ' << p;
  return out.str();
}

Scene read_colmap(const std::string& path, const std::string& image_dir) {
  const fs::path folder = model_folder(path);
  colmap::Model model = read_model(folder);
  sort_images(&model);
  const bool binary = is_binary_model(folder);

  Scene scene;
  scene.format = "colmap";
  scene.producer = binary ? "COLMAP (binary model)" : "COLMAP (text model)";
  scene.source = path;
  const std::string image_folder =
      choose_image_folder(fs::absolute(folder), image_dir, model.images.front().name, &scene);
  for (const colmap::Image& image : model.images) {
    auto cam = model.cameras.find(image.camera_id);
    if (cam == model.cameras.end())
      throw Error("image " + std::to_string(image.id) + " ('" + image.name +
                      "') refers to camera " + std::to_string(image.camera_id) + ", which " +
                      model.cameras_file + " does not define",
                  model.images_file, image.line);
    View view;
    view.label = image.name;
    view.camera = cam->second.intrinsics;
    view.camera.R = image.R;
    view.camera.t = image.t;
    view.image_path = resolve(image.name, image_folder);
    scene.views.push_back(std::move(view));
  }
  if (model.has_points)
    attach_sparse_points(model, &scene);
  else
    scene.warnings.push_back("no points3D file: the sparse points cannot check the cameras");
  attach_mesh(fs::absolute(folder), &scene);
  return scene;
}

void write_colmap(const Scene& scene, const std::string& folder, bool overwrite) {
  const fs::path dir = fs::absolute(folder).lexically_normal();
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error("is a file; a COLMAP model is a folder", folder);
  if (scene.views.empty())
    throw Error("the scene has no view; a COLMAP model needs at least one image", folder);
  // Everything that can fail is checked before the first file is written.
  for (const View& v : scene.views) v.image_file("a COLMAP model");
  const ColmapModelText text = build_model_text(scene, dir);
  const std::string cameras = (dir / "cameras.txt").string();
  const std::string images = (dir / "images.txt").string();
  const std::string points = (dir / "points3D.txt").string();
  const std::string mesh = (dir / "meshed.ply").string();
  for (const auto& target : {cameras, images, points}) check_can_write(target, overwrite);
  if (!scene.mesh.empty()) check_can_write(mesh, overwrite);

  fs::create_directories(dir, ec);
  if (ec) throw Error("cannot create folder: " + ec.message(), folder);
  // Each file is written atomically; if a later one fails (disk full), the
  // ones this call created are removed, so no partial model is left.
  std::vector<std::string> created;
  auto track = [&](const std::string& file, const std::function<void()>& write) {
    const bool existed = fs::exists(file, ec);
    write();
    if (!existed) created.push_back(file);
  };
  try {
    track(cameras, [&] {
      write_atomically(cameras, [&](std::ostream& out) { write_cameras_txt(out, text); }, overwrite);
    });
    track(images, [&] {
      write_atomically(images, [&](std::ostream& out) { write_images_txt(out, text); }, overwrite);
    });
    track(points, [&] {
      write_atomically(points, [](std::ostream& out) { write_points3d_txt(out); }, overwrite);
    });
    if (!scene.mesh.empty()) {
      PlyWriteOptions options;
      options.overwrite = overwrite;
      track(mesh, [&] { write_ply(scene.mesh, mesh, options); });
    }
  } catch (...) {
    for (const auto& file : created) fs::remove(file, ec);
    throw;
  }
}

}  // namespace meshnbv::io
