#include "commands.h"

#include <filesystem>
#include <iostream>

#include "meshnbv/io/file_util.h"

namespace meshnbv::cli {

void SceneInput::add_to(CLI::App* cmd) {
  cmd->add_option("scene", path,
                  "Scene: a .mlp project, a .json scene, a Middlebury folder (*_par.txt), a COLMAP "
                  "model folder (text or binary), Bundler's bundle.out, Metashape's cameras .xml, "
                  "OpenMVG's sfm_data.json or Meshroom's .sfm / sfm.json")
      ->required();
  cmd->add_option("--format", format, "Scene format instead of guessing from the path")
      ->check(CLI::IsMember({"auto", "mlp", "json", "middlebury", "colmap", "bundler", "metashape",
                             "openmvg", "alicevision"}));
  cmd->add_option("--mesh", mesh, "Mesh (.ply, .obj, .off) to use instead of the scene's own");
  cmd->add_option("--image-dir", image_dir, "Folder of the images (COLMAP, Bundler, Metashape, OpenMVG, AliceVision; the last three search it recursively by file name)");
}

Scene SceneInput::read() const {
  io::SceneReadOptions options;
  options.format = io::parse_scene_format(format);
  options.mesh_path = mesh;
  options.image_dir = image_dir;
  Scene scene = io::read_scene(path, options);
  if (print_warnings)
    for (const auto& w : scene.warnings) std::cerr << "warning: " << w << "\n";
  return scene;
}

void check_colmap_output(const std::string& folder, bool overwrite) {
  io::check_can_write_folder(folder);
  for (const char* file : {"cameras.txt", "images.txt", "points3D.txt"})
    io::check_can_write((std::filesystem::path(folder) / file).string(), overwrite);
}

}  // namespace meshnbv::cli
