// Middlebury multi-view stereo camera files (*_par.txt), e.g. templeRing:
//   N
//   name k11 k12 k13 k21 k22 k23 k31 k32 k33 r11 .. r33 t1 t2 t3   (N lines)
// The projection of each image is K [R | t] with the origin at the top-left
// pixel, so R and t are already our x_cam = R X + t (camera along +z, y down).
// K's principal point is used as given: the set was calibrated with pixel
// centres at integer coordinates (the OpenCV/Bouguet convention), which is
// ours, so no half-pixel shift applies (unlike COLMAP).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

constexpr std::size_t kParFields = 22;  // name + 9 (K) + 9 (R) + 3 (t)

struct ParEntry {
  std::string name;
  Mat3 K, R;
  Vec3 t;
  long line = -1;
};

std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// `path` is the par file itself, or a folder holding exactly one *_par.txt
// (a Middlebury folder also holds *_ang.txt, which is not a camera file).
std::string find_par_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("no such file or folder", path);
  if (!fs::is_directory(path, ec)) return path;
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(path, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 8 && name.compare(name.size() - 8, 8, "_par.txt") == 0)
      found.push_back(entry.path().string());
  }
  std::sort(found.begin(), found.end());
  if (found.empty())
    throw Error("folder holds no Middlebury camera file (*_par.txt); pass the par file itself",
                path);
  if (found.size() > 1) {
    std::string names;
    for (const auto& f : found)
      names += (names.empty() ? "" : ", ") + fs::path(f).filename().string();
    throw Error("folder holds several Middlebury camera files (" + names + "); pass the one to use",
                path);
  }
  return found.front();
}

Mat3 parse_matrix(const std::vector<std::string>& tokens, std::size_t first, const char* prefix,
                  const std::string& file, long line) {
  Mat3 m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      m(r, c) = parse_double(tokens[first + 3 * r + c], file, line,
                             prefix + std::to_string(r + 1) + std::to_string(c + 1));
  return m;
}

ParEntry parse_par_line(const std::vector<std::string>& tokens, const std::string& file,
                        long line) {
  if (tokens.size() != kParFields)
    throw Error("expected 22 fields (name + 21 numbers), got " + std::to_string(tokens.size()),
                file, line);
  ParEntry e;
  e.name = tokens[0];
  e.line = line;
  e.K = parse_matrix(tokens, 1, "k", file, line);
  e.R = parse_matrix(tokens, 10, "r", file, line);
  for (int i = 0; i < 3; ++i)
    e.t[i] = parse_double(tokens[19 + i], file, line, "t" + std::to_string(i + 1));
  return e;
}

std::vector<ParEntry> parse_par_file(const std::string& file) {
  TextTokens text(read_file(file), file);
  std::vector<std::string> tokens;
  if (!text.next_line(&tokens)) throw Error("empty camera file", file);
  if (tokens.size() != 1)
    throw Error("the first line must hold only the number of cameras, got " +
                    std::to_string(tokens.size()) + " fields",
                file, text.line());
  const long long declared = parse_int(tokens[0], file, text.line(), "the number of cameras");
  if (declared <= 0)
    throw Error("the number of cameras must be positive, got " + tokens[0], file, text.line());
  // Entries grow with the lines actually present: the declared count is only
  // compared, never used to allocate.
  std::vector<ParEntry> entries;
  while (text.next_line(&tokens)) entries.push_back(parse_par_line(tokens, file, text.line()));
  if (static_cast<long long>(entries.size()) != declared)
    throw Error("declares " + std::to_string(declared) + " cameras but holds " +
                    std::to_string(entries.size()) + " camera lines",
                file, 1);
  return entries;
}

// K must be upper triangular without skew (our pinhole model has none);
// a K scaled by k33 != 1 is normalised.
void intrinsics_from_K(const ParEntry& e, const std::string& file, PinholeCamera* cam) {
  Mat3 K = e.K;
  if (K(2, 2) == 0.0) throw Error("k33 is 0: not an intrinsic matrix", file, e.line, e.name);
  K /= K(2, 2);
  if (K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0)
    throw Error("K must be upper triangular (k21 = k31 = k32 = 0)", file, e.line, e.name);
  for (int i = 0; i < 2; ++i) {
    const double f = K(i, i);
    const std::string which = i == 0 ? "k11" : "k22";
    if (f == 0.0) throw Error("zero focal length (" + which + " = 0)", file, e.line, e.name);
    if (f < 0.0)
      throw Error("negative focal length (" + which + " = " + number_text(f) + ") is not supported",
                  file, e.line, e.name);
  }
  if (std::abs(K(0, 1)) > 1e-9 * K(0, 0))
    throw Error("skew (k12 = " + number_text(K(0, 1)) + ") is not supported by the pinhole model",
                file, e.line, e.name);
  cam->fx = K(0, 0);
  cam->fy = K(1, 1);
  cam->cx = K(0, 2);
  cam->cy = K(1, 2);
}

// All images of a set share one size (one camera on the gantry): the first
// image present gives it. Missing images turn their views into candidates
// (no image) with a warning; no image at all is an error, since the size is
// then unknown.
void assign_images(const std::vector<ParEntry>& entries, const std::string& folder,
                   const std::string& par_file, Scene* scene, int* width, int* height) {
  std::vector<std::string> missing;
  std::string sized_from;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string image =
        fs::absolute(resolve(entries[i].name, folder)).lexically_normal().string();
    std::error_code ec;
    if (!fs::is_regular_file(image, ec)) {
      missing.push_back(entries[i].name);
      continue;
    }
    scene->views[i].image_path = image;
    if (sized_from.empty()) sized_from = image;
  }
  if (sized_from.empty())
    throw Error("none of the " + std::to_string(entries.size()) +
                    " images is present (looked for '" + entries.front().name + "' ... in " +
                    folder + "); the image size comes from the image files",
                par_file);
  auto image = scene->images->get(sized_from);
  *width = image->width();
  *height = image->height();
  if (missing.empty()) return;
  std::string list;
  for (std::size_t i = 0; i < missing.size() && i < 5; ++i) list += (i ? ", " : "") + missing[i];
  if (missing.size() > 5) list += ", ...";
  scene->warnings.push_back(std::to_string(missing.size()) + " of " +
                            std::to_string(entries.size()) + " images missing in " + folder + " (" +
                            list + "); those views are kept as candidates without image");
}

void check_camera(const PinholeCamera& cam, const ParEntry& e, const std::string& file) {
  try {
    cam.check("camera '" + e.name + "'");
  } catch (const Error& err) {
    throw Error(err.reason(), file, e.line);
  }
}

}  // namespace

Scene read_middlebury(const std::string& path) {
  const std::string par_file = find_par_file(path);
  const std::vector<ParEntry> entries = parse_par_file(par_file);
  const std::string folder = fs::absolute(par_file).parent_path().string();

  Scene scene;
  scene.format = "middlebury";
  scene.source = path;
  scene.views.resize(entries.size());
  std::vector<PinholeCamera> intrinsics(entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i)
    intrinsics_from_K(entries[i], par_file, &intrinsics[i]);

  int width = 0, height = 0;
  assign_images(entries, folder, par_file, &scene, &width, &height);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    View& view = scene.views[i];
    view.label = entries[i].name;
    view.camera = intrinsics[i];
    view.camera.width = width;
    view.camera.height = height;
    view.camera.R = entries[i].R;
    view.camera.t = entries[i].t;
    check_camera(view.camera, entries[i], par_file);
  }
  return scene;
}

}  // namespace meshnbv::io
