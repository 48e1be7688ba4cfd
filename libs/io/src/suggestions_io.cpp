#include "meshnbv/io/suggestions_io.h"

#include <filesystem>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

std::vector<View> suggestion_views(const SuggestResult& result) {
  std::vector<View> views;
  for (const auto& s : result.suggestions) {
    View v;
    v.label = s.label;
    v.camera = s.camera;
    views.push_back(v);
  }
  return views;
}

}  // namespace

void write_suggestions_mlp(const Scene& scene, const SuggestResult& result, const std::string& path,
                           bool overwrite) {
  check_can_write(path, overwrite);
  // Before the mesh is written: a project cannot reference an in-memory image.
  for (const View& v : scene.views) v.image_file("a MeshLab project (.mlp)");
  Scene out;
  out.views = scene.views;
  for (auto& v : suggestion_views(result)) out.views.push_back(v);
  std::string mesh_file = scene.mesh_path;
  std::error_code ec;
  if (mesh_file.empty() || !fs::exists(mesh_file, ec)) {
    const fs::path p(path);
    mesh_file = (p.parent_path() / (p.stem().string() + "_mesh.ply")).string();
    PlyWriteOptions ply;
    ply.overwrite = overwrite;
    write_ply(scene.mesh, mesh_file, ply);
  }
  write_mlp(out, path, mesh_file, overwrite);
}

void write_suggestions_colmap(const SuggestResult& result, const std::string& folder, bool overwrite) {
  Scene s;
  s.views = suggestion_views(result);
  write_colmap(s, folder, overwrite);
}

}  // namespace meshnbv::io
