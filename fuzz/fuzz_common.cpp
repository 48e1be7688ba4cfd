#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::fuzz {
namespace {

const char kPyramidPly[] =
    "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
    "property float z\nelement face 5\nproperty list uchar int vertex_indices\n"
    "property float quality\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
    "4 0 3 2 1 0.5\n3 0 1 4 1\n3 1 2 4 1.5\n3 2 3 4 2\n3 3 0 4 nan\n";
const char kPyramidObj[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nf 1 4 3 2\nf 1 2 5\nf 2 3 5\n"
    "f 3 4 5\nf 4 1 5\n";
const char kPyramidOff[] =
    "OFF\n5 5 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n"
    "3 2 3 4\n3 3 0 4\n";

void put(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

void put_image(const fs::path& path, int width, int height) {
  fs::create_directories(path.parent_path());
  Image image(width, height, 1);
  for (std::size_t i = 0; i < image.bytes(); ++i) image.data()[i] = static_cast<std::uint8_t>(i * 37);
  image.save(path.string());
}

std::string make_scratch() {
  const char* shm = "/dev/shm";
  const char* tmp = std::getenv("TMPDIR");
  std::error_code ec;
  const fs::path root = fs::is_directory(shm, ec) ? fs::path(shm) : fs::path(tmp ? tmp : "/tmp");
  // Folders left by crashed runs (a crash skips the atexit cleanup).
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    const std::string name = entry.path().filename().string();
    const std::string prefix = "meshnbv_fuzz_";
    if (name.compare(0, prefix.size(), prefix) == 0 &&
        !fs::exists("/proc/" + name.substr(prefix.size()), ec))
      fs::remove_all(entry.path(), ec);
  }
  const fs::path dir = root / ("meshnbv_fuzz_" + std::to_string(::getpid()));
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  put(dir / "mesh.ply", kPyramidPly);
  put(dir / "mesh.obj", kPyramidObj);
  put(dir / "mesh.off", kPyramidOff);
  put_image(dir / "image.png", 8, 6);
  put_image(dir / "images" / "a.png", 8, 6);
  put_image(dir / "images" / "b.png", 8, 6);
  put_image(dir / "c.png", 6, 8);
  put_image(dir / "v0.png", 64, 48);
  put_image(dir / "v1.png", 64, 48);
  put(dir / "broken.png", "not a png");
  return dir.string();
}

std::string* g_scratch = nullptr;

void remove_scratch() {
  std::error_code ec;
  if (g_scratch) fs::remove_all(*g_scratch, ec);
}

std::map<std::string, TargetFn>& registry() {
  static std::map<std::string, TargetFn> targets;
  return targets;
}

// Bitwise, except that every NaN equals every NaN: the readers go through
// double, which quiets signalling NaNs (changing their bits), and ASCII
// writes any NaN as "nan".
bool same_floats(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i]) && std::isnan(b[i])) continue;
    if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) return false;
  }
  return true;
}

void check_same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  FUZZ_CHECK(a.vertices == b.vertices);
  FUZZ_CHECK(a.faces == b.faces);
  FUZZ_CHECK(a.face_colors == b.face_colors);
  FUZZ_CHECK(a.face_attributes.size() == b.face_attributes.size());
  for (const auto& [name, values] : a.face_attributes) {
    const std::vector<float>* other = b.face_attribute(name);
    FUZZ_CHECK(other != nullptr);
    FUZZ_CHECK(same_floats(values, *other));
  }
}

bool close(double a, double b, double tol) {
  return std::abs(a - b) <= tol * std::max({1.0, std::abs(a), std::abs(b)});
}

// `tol`: relative, for the intrinsics; `pose_tol` for R and the centre.
// The readers accept R up to |R R^T - I| = 1e-4 (PinholeCamera::check), and
// formats that store the centre (.mlp) or a quaternion (COLMAP) instead of
// R and t move such a camera by that much: a loose pose_tol there.
void check_close_camera(const PinholeCamera& a, const PinholeCamera& b, double tol,
                        double pose_tol) {
  FUZZ_CHECK(a.width == b.width && a.height == b.height);
  FUZZ_CHECK(close(a.fx, b.fx, tol) && close(a.fy, b.fy, tol));
  FUZZ_CHECK(close(a.cx, b.cx, tol) && close(a.cy, b.cy, tol));
  FUZZ_CHECK(a.lens == b.lens);
  FUZZ_CHECK(close(a.k1, b.k1, tol) && close(a.k2, b.k2, tol) && close(a.k3, b.k3, tol));
  FUZZ_CHECK(close(a.k4, b.k4, tol) && close(a.k5, b.k5, tol) && close(a.k6, b.k6, tol));
  FUZZ_CHECK(close(a.p1, b.p1, tol) && close(a.p2, b.p2, tol) && close(a.skew, b.skew, tol));
  FUZZ_CHECK((a.R - b.R).norm() <= pose_tol);
  FUZZ_CHECK(close(a.center().norm(), b.center().norm(), pose_tol));
}

std::string normal(const std::string& path) {
  return path.empty() ? path : fs::absolute(path).lexically_normal().string();
}

// Writes `scene` in `format` under scratch()/rt and reads it back; a writer
// may refuse (Error) what it cannot represent, but what it writes must read
// back as the same scene.
void round_trip(const Scene& scene, io::SceneFormat format, const std::string& out,
                double tol, double pose_tol) {
  const std::string path = scratch() + "/rt/" + out;
  std::error_code ec;
  fs::remove_all(scratch() + "/rt", ec);
  io::SceneWriteOptions w;
  w.format = format;
  w.overwrite = true;
  try {
    io::write_scene(scene, path, w);
  } catch (const Error&) {
    return;
  }
  io::SceneReadOptions r;
  r.format = format;
  const Scene back = io::read_scene(path, r);
  FUZZ_CHECK(back.views.size() == scene.views.size());
  FUZZ_CHECK(back.mesh.faces == scene.mesh.faces);
  for (std::size_t i = 0; i < scene.views.size(); ++i) {
    check_close_camera(scene.views[i].camera, back.views[i].camera, tol, pose_tol);
    if (format == io::SceneFormat::Json) {
      FUZZ_CHECK(back.views[i].label == scene.views[i].label);
      FUZZ_CHECK(back.views[i].used == scene.views[i].used);
      FUZZ_CHECK(normal(back.views[i].image_path) == normal(scene.views[i].image_path));
    }
  }
}

}  // namespace

bool register_target(const char* name, TargetFn fn) {
  registry()[name] = fn;
  return true;
}

TargetFn find_target(const std::string& name) {
  auto it = registry().find(name);
  return it == registry().end() ? nullptr : it->second;
}

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  for (const auto& entry : registry()) names.push_back(entry.first);
  return names;
}

const std::string& scratch() {
  if (!g_scratch) {
    g_scratch = new std::string(make_scratch());
    std::atexit(remove_scratch);
  }
  return *g_scratch;
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = scratch() + "/" + name;
  put(path, text);
  return path;
}

std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  return write_text(name, std::string(reinterpret_cast<const char*>(data), size));
}

void split_two(const std::uint8_t* data, std::size_t size, std::string* first,
               std::string* second) {
  const std::string all(reinterpret_cast<const char*>(data), size);
  const std::size_t at = all.find("\n%%%%\n");
  if (at == std::string::npos) {
    *first = all;
    second->clear();
    return;
  }
  *first = all.substr(0, at + 1);
  *second = all.substr(at + 6);
}

void exercise_mesh(const TriangleMesh& mesh) {
  mesh.validate("fuzz");
  const MeshCheck check = check_mesh(mesh);
  FUZZ_CHECK(check.invalid_faces == 0 && check.nonfinite_vertices == 0);
  (void)mesh.total_area();
  (void)mesh.bounding_box();
  for (bool binary : {true, false}) {
    io::PlyWriteOptions options;
    options.binary = binary;
    options.double_precision = true;
    const std::string path = scratch() + (binary ? "/rt_binary.ply" : "/rt_ascii.ply");
    try {
      io::write_ply(mesh, path, options);
    } catch (const Error&) {
      continue;  // e.g. an attribute name PLY cannot hold: refused with a message
    }
    check_same_mesh(mesh, io::read_ply(path));
  }
}

void exercise_scene(const Scene& scene) {
  scene.validate();
  if (!scene.mesh.empty()) (void)check_mesh(scene.mesh);
  for (const View& v : scene.views) {
    (void)v.camera.center();
    (void)v.camera.frustum_corners(1.0);
  }
  const ReprojectionStats r = reprojection_error(scene);
  FUZZ_CHECK(r.observations == 0 || (r.median >= 0 && r.median <= r.max));
  // JSON holds our camera exactly; .mlp and COLMAP convert (rounding).
  round_trip(scene, io::SceneFormat::Json, "scene.json", 0.0, 0.0);
  round_trip(scene, io::SceneFormat::Mlp, "scene.mlp", 1e-9, 2e-3);
  round_trip(scene, io::SceneFormat::Colmap, "colmap", 1e-9, 2e-3);
}

void check_failed(const char* what, const char* file, int line) {
  std::fprintf(stderr, "fuzz: check failed: %s (%s:%d)\n", what, file, line);
  std::abort();
}

}  // namespace meshnbv::fuzz
