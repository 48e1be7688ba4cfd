#include "meshnbv/io/scene_io.h"
#include "meshnbv/enum_names.h"

#include <filesystem>
#include <fstream>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {

constexpr detail::EnumTable<SceneFormat, 9> kSceneFormats = {
    {"auto", SceneFormat::Auto},
    {"mlp", SceneFormat::Mlp},
    {"json", SceneFormat::Json},
    {"middlebury", SceneFormat::Middlebury},
    {"colmap", SceneFormat::Colmap},
    {"bundler", SceneFormat::Bundler},
    {"metashape", SceneFormat::Metashape},
    {"openmvg", SceneFormat::OpenMvg},
    {"alicevision", SceneFormat::AliceVision},
};

SceneFormat parse_scene_format(const std::string& name) {
  return detail::parse_enum(name, kSceneFormats, "scene format");
}

std::string scene_format_name(SceneFormat format) {
  return detail::enum_name(format, kSceneFormats);
}

namespace {
bool has_par_file(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 8 && name.compare(name.size() - 8, 8, "_par.txt") == 0) return true;
  }
  return false;
}

// A .json file: ours, OpenMVG's sfm_data.json or AliceVision's sfm.json,
// told apart by keys near the start of the file.
SceneFormat sniff_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  if (head.find("\"sfm_data_version\"") != std::string::npos) return SceneFormat::OpenMvg;
  if (head.find("\"meshnbv-scene\"") == std::string::npos &&
      (head.find("\"viewId\"") != std::string::npos ||
       head.find("\"intrinsicId\"") != std::string::npos ||
       head.find("\"featuresFolders\"") != std::string::npos))
    return SceneFormat::AliceVision;
  return SceneFormat::Json;
}
}  // namespace

SceneFormat detect_scene_format(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  if (!fs::exists(p, ec)) throw Error("scene not found", path);
  if (fs::is_directory(p, ec)) {
    if (fs::exists(p / "cameras.txt") && fs::exists(p / "images.txt")) return SceneFormat::Colmap;
    if (fs::exists(p / "cameras.bin") && fs::exists(p / "images.bin")) return SceneFormat::Colmap;
    if (fs::exists(p / "bundle.out")) return SceneFormat::Bundler;
    if (has_par_file(p)) return SceneFormat::Middlebury;
    throw Error("cannot tell the scene format of this folder: expected cameras.txt + images.txt "
                "or cameras.bin + images.bin (COLMAP), bundle.out (Bundler) or *_par.txt (Middlebury); use --format",
                path);
  }
  const std::string ext = extension_lower(path);
  const std::string name = p.filename().string();
  if (ext == ".mlp") return SceneFormat::Mlp;
  if (ext == ".json") return sniff_json(path);
  if (ext == ".sfm") return SceneFormat::AliceVision;
  if (ext == ".xml") return SceneFormat::Metashape;
  if (ext == ".out") return SceneFormat::Bundler;
  if (name.size() > 8 && name.compare(name.size() - 8, 8, "_par.txt") == 0)
    return SceneFormat::Middlebury;
  for (const char* colmap : {"cameras.txt", "images.txt", "points3D.txt", "cameras.bin", "images.bin",
                             "points3D.bin"})
    if (name == colmap) return SceneFormat::Colmap;
  throw Error("cannot tell the scene format from the name: expected .mlp, .json (ours, OpenMVG "
              "sfm_data.json, AliceVision sfm.json), .sfm (Meshroom), .xml (Metashape cameras), "
              "bundle.out, *_par.txt or a COLMAP folder; use --format",
              path);
}

Scene read_scene(const std::string& path, const SceneReadOptions& options) {
  SceneFormat format =
      options.format == SceneFormat::Auto ? detect_scene_format(path) : options.format;
  std::string where = path;
  // A COLMAP model is a folder; accept its cameras.txt/images.txt too.
  if (format == SceneFormat::Colmap && !fs::is_directory(path))
    where = fs::path(path).parent_path().string();
  Scene scene;
  switch (format) {
    case SceneFormat::Mlp: scene = read_mlp(where); break;
    case SceneFormat::Json: scene = read_json_scene(where); break;
    case SceneFormat::Middlebury: scene = read_middlebury(where); break;
    case SceneFormat::Colmap: scene = read_colmap(where, options.image_dir); break;
    case SceneFormat::Bundler: scene = read_bundler(where, options.image_dir); break;
    case SceneFormat::Metashape: scene = read_metashape(where, options.image_dir); break;
    case SceneFormat::OpenMvg: scene = read_openmvg(where, options.image_dir); break;
    case SceneFormat::AliceVision: scene = read_alicevision(where, options.image_dir); break;
    case SceneFormat::Auto: break;
  }
  if (!options.mesh_path.empty()) {
    scene.mesh = read_mesh(options.mesh_path);
    scene.mesh_path = options.mesh_path;
  }
  scene.validate();
  const std::string frame = mesh_frame_warning(scene);
  if (!frame.empty()) scene.warnings.push_back(frame);
  return scene;
}

SceneFormat scene_output_format(const std::string& path, SceneFormat format) {
  if (format != SceneFormat::Auto) return format;
  const std::string ext = extension_lower(path);
  if (ext == ".mlp") return SceneFormat::Mlp;
  if (ext == ".json") return SceneFormat::Json;
  if (ext.empty()) return SceneFormat::Colmap;  // a folder
  throw Error("cannot tell the output format from the name: use .mlp, .json or a folder (COLMAP)",
              path);
}

void write_scene(const Scene& scene, const std::string& path, const SceneWriteOptions& options) {
  const SceneFormat format = scene_output_format(path, options.format);
  if (format == SceneFormat::Colmap) {
    write_colmap(scene, path, options.overwrite);
    return;
  }
  if (format != SceneFormat::Mlp && format != SceneFormat::Json)
    throw Error(scene_format_name(format) + " is read-only; write .mlp, .json or COLMAP", path);
  // The mesh goes beside the project file, so the project is self-contained.
  std::string mesh_file;
  if (!scene.mesh.empty()) {
    const fs::path p(path);
    mesh_file = (p.parent_path() / (p.stem().string() + "_mesh.ply")).string();
  }
  check_can_write(path, options.overwrite);
  // Before the mesh is written: a file cannot reference an in-memory image.
  for (const auto& v : scene.views)
    v.image_file(format == SceneFormat::Mlp ? "a MeshLab project (.mlp)" : "a JSON scene");
  if (format == SceneFormat::Mlp && !mlp_unsupported_reason(scene).empty())
    throw Error(mlp_unsupported_reason(scene), path);
  if (!mesh_file.empty()) check_can_write(mesh_file, options.overwrite);
  std::error_code ec;
  const bool mesh_existed = !mesh_file.empty() && fs::exists(mesh_file, ec);
  if (!mesh_file.empty()) {
    PlyWriteOptions ply;
    ply.overwrite = options.overwrite;
    write_ply(scene.mesh, mesh_file, ply);
  }
  try {
    if (format == SceneFormat::Mlp)
      write_mlp(scene, path, mesh_file, options.overwrite);
    else
      write_json_scene(scene, path, mesh_file, options.overwrite);
  } catch (...) {
    // No mesh without its project: remove the one this call created.
    if (!mesh_file.empty() && !mesh_existed) fs::remove(mesh_file, ec);
    throw;
  }
}

}  // namespace meshnbv::io
