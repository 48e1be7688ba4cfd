// meshnbv synth: a synthetic project with ground truth.
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/synth/project.h"
#include "progress_bar.h"

namespace meshnbv::cli {

void add_synth_command(CLI::App& app) {
  struct Args {
    std::string scene, out, mesh, layout = "ring", size = "640x480";
    std::vector<std::string> degrade;
    int views = 24, samples = 4;
    std::uint64_t seed = 1;
    double edge = 0.0;
    bool depth = false, overwrite = false, quiet = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "synth", "Make a synthetic project with ground truth: scene, degraded reconstruction, "
               "rendered views, .mlp and JSON");
  cmd->add_option("scene", a->scene, "building, fortress, city, or object (with --mesh)")
      ->required()
      ->check(CLI::IsMember({"building", "fortress", "city", "object"}));
  cmd->add_option("--out", a->out, "Output folder")->required();
  cmd->add_option("--mesh", a->mesh, "Mesh for the 'object' scene (.ply, .obj, .off)");
  cmd->add_option("--views", a->views, "Number of views")->capture_default_str();
  cmd->add_option("--layout", a->layout, "Camera layout")
      ->check(CLI::IsMember({"ring", "hemisphere", "orbit", "grid"}))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--degrade", a->degrade,
                  "Degradations, each kind[:strength[:radius]] with kind noise|dent|bump|hole|"
                  "decimate (default: noise and dent)");
  cmd->add_option("--samples-per-pixel", a->samples, "Supersampling")->capture_default_str();
  cmd->add_option("--edge-length", a->edge, "Triangle edge length in metres (0 = scene default)");
  cmd->add_option("--seed", a->seed, "Seed of everything random")->capture_default_str();
  cmd->add_flag("--depth", a->depth, "Also write depth maps (32-bit TIFF)");
  cmd->add_flag("--overwrite", a->overwrite, "Write into a non-empty folder");
  cmd->add_flag("--quiet", a->quiet, "No progress output");
  cmd->callback([a]() {
    synth::SynthOptions o;
    o.scene = a->scene;
    o.mesh_file = a->mesh;
    o.seed = a->seed;
    o.generator.edge_length = a->edge;
    o.cameras.count = a->views;
    o.cameras.layout = synth::parse_camera_layout(a->layout);
    char x = 0;
    std::istringstream size(a->size);
    if (!(size >> o.cameras.width >> x >> o.cameras.height) || x != 'x' || !size.eof())
      throw Error("--size must look like 640x480, got '" + a->size + "'");
    for (const auto& d : a->degrade) o.degradations.push_back(synth::parse_degradation(d));
    o.render.samples_per_pixel = a->samples;
    o.write_depth = a->depth;
    o.overwrite = a->overwrite;
    o.check();
    io::check_can_write_folder(a->out);
    ProgressBar bar(a->quiet);
    const auto p = synth::write_synthetic_project(o, a->out, bar.callback());
    bar.finish();
    std::cout << "truth " << p.truth.num_faces() << " faces, degraded " << p.scene.mesh.num_faces()
              << " faces, " << p.scene.views.size() << " views\n"
              << "project: " << a->out << "/project.mlp (also scene.json, README.md)\n";
  });
}

}  // namespace meshnbv::cli
