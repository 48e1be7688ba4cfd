// Bundler v0.3 output (bundle.out) with its image list (list.txt).
//
// bundle.out: "# Bundle file v0.3", "num_cameras num_points", then per
// camera "f k1 k2", three rows of R and t, then the points (not needed
// here, so never read). Bundler's camera looks along -z with y up:
// P = R X + t, p = -P / P.z, p' = f (1 + k1 |p|^2 + k2 |p|^4) p, measured
// from the image centre with y up. In our frame (x right, y down, +z ahead)
// the camera point is diag(1, -1, -1) P, whose normalised coordinates are
// (p.x, -p.y): the same radius, so k1 and k2 carry over unchanged, and
// R = diag(1,-1,-1) R_b, t = diag(1,-1,-1) t_b, fx = fy = f. The image
// centre is (W-1)/2, (H-1)/2 in our pixel-centre coordinates, so W and H
// are read from the image files.
// Unregistered cameras are written by Bundler as all zeros (f = 0).
#include <filesystem>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

// A camera takes 15 numbers; at least "0 " each.
constexpr std::uintmax_t kMinBytesPerCamera = 30;

struct BundlerCamera {
  double f = 0, k1 = 0, k2 = 0;
  Mat3 R;
  Vec3 t;
  long line = -1;  // of its "f k1 k2" line
};

struct ListEntry {
  std::string path;  // as written in list.txt
  long line = -1;
};

// Numbers across line breaks, remembering the line of the last one.
class NumberReader {
 public:
  explicit NumberReader(TextTokens* text) : text_(text) {}
  bool next(double* value, const std::string& what) {
    while (index_ >= tokens_.size()) {
      if (!text_->next_line(&tokens_)) return false;
      index_ = 0;
    }
    *value = parse_double(tokens_[index_++], text_->file(), text_->line(), what);
    return true;
  }
  long line() const { return text_->line(); }

 private:
  TextTokens* text_;
  std::vector<std::string> tokens_;
  std::size_t index_ = 0;
};

// `path`: bundle.out, or a folder holding it (directly or in bundle/, the
// layout of Bundler's own scripts).
std::string find_bundle_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("no such file or folder", path);
  if (!fs::is_directory(path, ec)) return path;
  for (const fs::path& c :
       {fs::path(path) / "bundle.out", fs::path(path) / "bundle" / "bundle.out"})
    if (is_file(c)) return c.string();
  throw Error("folder holds no bundle.out (nor bundle/bundle.out)", path);
}

std::string find_list_file(const std::string& bundle_file) {
  const fs::path folder = fs::absolute(bundle_file).parent_path();
  const fs::path beside = folder / "list.txt";
  const fs::path above = (folder / ".." / "list.txt").lexically_normal();
  if (is_file(beside)) return beside.string();
  if (is_file(above)) return above.string();
  throw Error("image list not found: looked for " + beside.string() + " and " + above.string(),
              bundle_file);
}

// Reads up to and including the "num_cameras num_points" line.
long long read_header(TextTokens* text, std::uintmax_t file_bytes) {
  const std::string& file = text->file();
  std::vector<std::string> tokens;
  if (!text->next_line(&tokens)) throw Error("empty bundle file", file);
  if (tokens[0][0] == '#') {
    const bool v03 = tokens.size() >= 4 && tokens[1] == "Bundle" && tokens[3] == "v0.3";
    if (!v03)
      throw Error("unsupported header; only '# Bundle file v0.3' is read", file, text->line());
    if (!text->next_line(&tokens)) throw Error("truncated: no 'num_cameras num_points' line", file);
  }
  if (tokens.size() != 2)
    throw Error(
        "expected 'num_cameras num_points', got " + std::to_string(tokens.size()) + " fields", file,
        text->line());
  const long long cameras = parse_int(tokens[0], file, text->line(), "num_cameras");
  const long long points = parse_int(tokens[1], file, text->line(), "num_points");
  if (cameras <= 0 || points < 0)
    throw Error("num_cameras must be positive and num_points non-negative, got " + tokens[0] +
                    " and " + tokens[1],
                file, text->line());
  if (static_cast<std::uintmax_t>(cameras) > file_bytes / kMinBytesPerCamera)
    throw Error("declares " + tokens[0] + " cameras but the file has only " +
                    std::to_string(file_bytes) + " bytes: truncated or not a bundle file",
                file, text->line());
  return cameras;
}

BundlerCamera read_camera(NumberReader* numbers, long long index, long long count,
                          const std::string& file) {
  double v[15];
  const char* names[] = {"f", "k1", "k2"};
  BundlerCamera cam;
  for (int i = 0; i < 15; ++i) {
    const std::string what =
        i < 3    ? names[i]
        : i < 12 ? "r" + std::to_string((i - 3) / 3 + 1) + std::to_string((i - 3) % 3 + 1)
                 : "t" + std::to_string(i - 11);
    if (!numbers->next(&v[i], "camera " + std::to_string(index) + " " + what))
      throw Error("truncated: the file ends inside camera " + std::to_string(index) + " of " +
                      std::to_string(count) + " (needs 15 numbers: f k1 k2, R, t)",
                  file, numbers->line());
    if (i == 0) cam.line = numbers->line();
  }
  cam.f = v[0];
  cam.k1 = v[1];
  cam.k2 = v[2];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) cam.R(r, c) = v[3 + 3 * r + c];
  cam.t = Vec3(v[12], v[13], v[14]);
  return cam;
}

std::vector<BundlerCamera> read_bundle(const std::string& file) {
  TextTokens text(read_file(file), file);
  const long long count = read_header(&text, file_size(file));
  NumberReader numbers(&text);
  std::vector<BundlerCamera> cameras;
  for (long long i = 0; i < count; ++i) cameras.push_back(read_camera(&numbers, i, count, file));
  return cameras;  // the points that follow are not needed
}

// One line per camera: "path [0 focal]"; only the path is used.
std::vector<ListEntry> read_list(const std::string& file) {
  TextTokens text(read_file(file), file);
  std::vector<ListEntry> entries;
  std::vector<std::string> tokens;
  while (text.next_line(&tokens)) entries.push_back({tokens[0], text.line()});
  return entries;
}

PinholeCamera to_our_camera(const BundlerCamera& b, int width, int height) {
  const Mat3 flip = Vec3(1.0, -1.0, -1.0).asDiagonal();
  PinholeCamera cam;
  cam.fx = cam.fy = b.f;
  cam.cx = 0.5 * (width - 1);
  cam.cy = 0.5 * (height - 1);
  cam.width = width;
  cam.height = height;
  cam.k1 = b.k1;
  cam.k2 = b.k2;
  cam.R = flip * b.R;
  cam.t = flip * b.t;
  return cam;
}

View make_view(const BundlerCamera& b, const ListEntry& entry, std::size_t index,
               const std::string& image_base, const std::string& bundle_file,
               const std::string& list_file, Scene* scene) {
  View view;
  view.label = entry.path;
  view.image_path = fs::absolute(resolve(entry.path, image_base)).lexically_normal().string();
  if (!is_file(view.image_path))
    throw Error("image of registered camera " + std::to_string(index) +
                    " not found: " + view.image_path +
                    " (its size fixes the principal point); pass the image "
                    "folder if the list's paths are relative to another one",
                list_file, entry.line);
  auto image = scene->images->get(view.image_path);
  view.camera = to_our_camera(b, image->width(), image->height());
  try {
    view.camera.check("camera " + std::to_string(index) + " ('" + entry.path + "')");
  } catch (const Error& e) {
    throw Error(e.reason(), bundle_file, b.line);
  }
  return view;
}

}  // namespace

Scene read_bundler(const std::string& path, const std::string& image_dir) {
  const std::string bundle_file = find_bundle_file(path);
  const std::string list_file = find_list_file(bundle_file);
  const std::vector<BundlerCamera> cameras = read_bundle(bundle_file);
  const std::vector<ListEntry> list = read_list(list_file);
  if (list.size() != cameras.size())
    throw Error("lists " + std::to_string(list.size()) + " images but " + bundle_file + " has " +
                    std::to_string(cameras.size()) +
                    " cameras; the list needs one line per camera, in the same order",
                list_file);
  const std::string image_base =
      image_dir.empty() ? fs::path(list_file).parent_path().string() : image_dir;

  Scene scene;
  scene.format = "bundler";
  scene.source = path;
  std::size_t unregistered = 0;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    if (cameras[i].f == 0.0) {
      ++unregistered;
      continue;
    }
    scene.views.push_back(
        make_view(cameras[i], list[i], i, image_base, bundle_file, list_file, &scene));
  }
  if (scene.views.empty())
    throw Error(
        "no registered camera (all " + std::to_string(cameras.size()) + " have focal length 0)",
        bundle_file);
  if (unregistered > 0)
    scene.warnings.push_back(std::to_string(unregistered) + " of " +
                             std::to_string(cameras.size()) +
                             " cameras are unregistered (focal length 0) and were skipped");
  return scene;
}

}  // namespace meshnbv::io
