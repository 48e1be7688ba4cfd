// meshnbv suggest: where to take the next photos.
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/io/pri_io.h"
#include "meshnbv/io/suggestions_io.h"
#include "meshnbv/options.h"
#include "meshnbv/planner.h"
#include "progress_bar.h"

namespace meshnbv::cli {
void add_suggest_options(CLI::App* cmd, OptionFlags* flags, SuggestOptions* options) {
  flags->add(cmd, suggest_option_table(), options);
}

void add_suggest_command(CLI::App& app) {
  struct Args {
    SceneInput input;
    PriOptions pri;
    SuggestOptions suggest;
    OptionFlags flags;
    ProgressChoice progress;
    std::string pri_file, candidates_from, out, mlp, frustums, colmap;
    bool overwrite = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "suggest", "Suggest the next views: score candidate poses with the next-best-view energy "
                 "over the worst faces (Morreale, Romanoni, Matteucci 2018)");
  a->input.add_to(cmd);
  cmd->add_option("--pri", a->pri_file, "Mesh with per-face quality = PRI (from meshnbv pri); "
                                        "otherwise PRI is computed");
  add_pri_options(cmd, &a->flags, &a->pri);
  add_suggest_options(cmd, &a->flags, &a->suggest);
  cmd->add_option("--candidates-from", a->candidates_from,
                  "Scene whose views are the candidates (given mode)");
  cmd->add_option("--out", a->out, "Suggestions as JSON")->required();
  cmd->add_option("--mlp", a->mlp, "The scene as a MeshLab project with one raster per suggestion");
  cmd->add_option("--frustums", a->frustums, "Frustum mesh of the suggestions (PLY, coloured by rank)");
  cmd->add_option("--colmap-model", a->colmap, "Folder for a COLMAP text model of the suggestions");
  cmd->add_flag("--overwrite", a->overwrite, "Replace existing output files");
  a->progress.add_to(cmd);
  cmd->callback([a]() {
    SuggestOptions& o = a->suggest;
    finish_options(a->flags, &a->pri, &o);
    if (!a->candidates_from.empty() && o.mode != CandidateMode::Given)
      throw Error("--candidates-from needs --candidates given");
    for (const std::string* p : {&a->out, &a->mlp, &a->frustums})
      if (!p->empty()) io::check_can_write(*p, a->overwrite);
    if (!a->colmap.empty()) check_colmap_output(a->colmap, a->overwrite);
    Scene scene = a->input.read();
    std::vector<View> given;  // read before the PRI is computed: a bad file fails early
    if (!a->candidates_from.empty()) given = io::read_scene(a->candidates_from, {}).views;
    ProgressBar bar(a->progress.silent(), a->progress.json());
    std::vector<float> pri;
    std::string pri_from;
    if (!a->pri_file.empty()) {
      // Only the PRI is taken from the file: the scene keeps its own mesh
      // (the file may hold it at float precision), which the file's must match.
      if (scene.mesh.empty()) {
        // A scene without a mesh (COLMAP, Middlebury): the PRI file's mesh is the one.
        scene.mesh = io::read_mesh(a->pri_file);
        scene.mesh.face_attributes.clear();
        scene.mesh.face_colors.clear();
        scene.mesh_path = a->pri_file;
      }
      pri = io::read_pri_for_mesh(a->pri_file, scene.mesh);
      pri_from = a->pri_file;
    } else {
      pri = scene_pri(scene, a->pri, bar.callback()).pri;
      pri_from = "computed (" + measure_name(a->pri.measure) + ")";
    }
    const SuggestResult r = suggest_views(scene, pri, o, given, bar.callback(), candidate_scorer());
    bar.finish();
    io::write_atomically(a->out, [&](std::ostream& out) {
      out << suggestions_json(r, o, {a->input.path, pri_from});
    }, a->overwrite);
    for (const auto& s : r.suggestions) {
      const Vec3 c = s.camera.center();
      std::cout << s.label << "  energy " << s.energy.total << "  (" << energy_terms_text(s.energy)
                << ")  centre (" << c.x() << ", " << c.y()
                << ", " << c.z() << ")  sees " << s.seen_faces.size() << "/"
                << r.regions[std::size_t(s.region)].faces.size() << " worst faces  [" << s.source << "]\n";
    }
    std::cout << r.candidates_evaluated << " candidate evaluations";
    if (r.candidates_generated)
      std::cout << " (" << r.candidates_generated << " sampled, " << r.rejected_inside
                << " rejected inside the mesh, " << r.rejected_too_close << " too close, "
                << r.rejected_below_ground << " below the ground)";
    std::cout << ", " << r.seconds << " s\nsuggestions: " << a->out << "\n";
    if (!a->mlp.empty()) {
      // An optional output that cannot hold the lens never fails the main job.
      const std::string no_mlp = io::mlp_unsupported_reason(scene);
      if (no_mlp.empty()) {
        io::write_suggestions_mlp(scene, r, a->mlp, a->overwrite);
        std::cout << "MeshLab project: " << a->mlp << "\n";
      } else {
        std::cerr << "warning: " << a->mlp << " skipped: " << no_mlp << "\n";
      }
    }
    if (!a->frustums.empty()) {
      io::PlyWriteOptions ply;
      ply.overwrite = a->overwrite;
      io::write_ply(frustum_mesh(r), a->frustums, ply);
      std::cout << "frustums: " << a->frustums << "\n";
    }
    if (!a->colmap.empty()) {
      io::write_suggestions_colmap(r, a->colmap, a->overwrite);
      std::cout << "COLMAP model: " << a->colmap << "\n";
    }
  });
}

}  // namespace meshnbv::cli
