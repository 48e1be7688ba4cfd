// meshnbv convert: between .mlp, COLMAP text model and our JSON.
#include <iostream>
#include <memory>

#include "commands.h"
#include "meshnbv/io/file_util.h"

namespace meshnbv::cli {

void add_convert_command(CLI::App& app) {
  auto input = std::make_shared<SceneInput>();
  auto output = std::make_shared<std::string>();
  auto out_format = std::make_shared<std::string>("auto");
  auto overwrite = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "convert", "Convert a scene: to .mlp, .json or a COLMAP text model folder");
  input->add_to(cmd);
  cmd->add_option("out", *output, "Output: file.mlp, file.json, or a folder (COLMAP text model)")
      ->required();
  cmd->add_option("--out-format", *out_format, "Output format instead of guessing from the name")
      ->check(CLI::IsMember({"auto", "mlp", "json", "colmap"}));
  cmd->add_flag("--overwrite", *overwrite, "Replace existing output files");
  cmd->callback([=]() {
    io::SceneWriteOptions options;
    options.format = io::scene_output_format(*output, io::parse_scene_format(*out_format));
    options.overwrite = *overwrite;
    if (options.format == io::SceneFormat::Colmap)
      check_colmap_output(*output, *overwrite);
    else
      io::check_can_write(*output, *overwrite);
    const Scene scene = input->read();
    io::write_scene(scene, *output, options);
    std::cout << "wrote " << scene.views.size() << " views"
              << (scene.mesh.empty() ? "" : " and the mesh") << " to " << *output << "\n";
  });
}

}  // namespace meshnbv::cli
