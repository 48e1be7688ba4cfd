// meshnbv pri: per-face Photo-consistency Reconstruction Index.
#include <iostream>
#include <memory>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/results.h"
#include "meshnbv/pri.h"
#include "progress_bar.h"

namespace meshnbv::cli {

void add_pri_options(CLI::App* cmd, PriOptions* o, std::string* measure) {
  cmd->add_option("--measure", *measure, "Photo-consistency measure")
      ->check(CLI::IsMember({"ssd", "ncc"}))
      ->capture_default_str();
  cmd->add_option("--samples-per-side", o->samples_per_side,
                  "Lattice subdivisions per face side (0 = automatic: the largest projected edge "
                  "in pixels, clamped to [2, 32])")
      ->capture_default_str();
  cmd->add_option("--max-views-per-face,--max-views", o->max_views_per_face,
                  "Views compared per face, smallest incidence angle first (0 = all)")
      ->capture_default_str();
  cmd->add_option("--max-incidence-angle", o->max_incidence_angle,
                  "Views seeing a face at a larger angle to its normal (degrees) are ignored")
      ->capture_default_str();
  cmd->add_option("--edge-margin", o->edge_margin,
                  "Keep the sampling lattice this many pixels inside the face in every view "
                  "(0 = the whole face)")
      ->capture_default_str();
  cmd->add_option("--check-interior-occlusion", o->check_interior_occlusion,
                  "Also require the face's centroid and edge midpoints unoccluded (true/false)")
      ->capture_default_str();
  cmd->add_flag("--color", o->color, "Compare R, G, B instead of luminance");
  cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
}

void add_pri_command(CLI::App& app) {
  struct Args {
    SceneInput input;
    PriOptions options;
    std::string measure = "ssd", out, json;
    std::size_t worst = 10;
    bool overwrite = false, quiet = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "pri", "Per-face Photo-consistency Reconstruction Index: which faces are poorly "
             "reconstructed (higher = worse)");
  a->input.add_to(cmd);
  add_pri_options(cmd, &a->options, &a->measure);
  cmd->add_option("--out", a->out,
                  "PLY with per-face quality = PRI (NaN where unobserved), pri_views and colour "
                  "(green best, red worst, grey unobserved)")
      ->required();
  cmd->add_option("--json", a->json, "Summary as JSON");
  cmd->add_option("--worst", a->worst, "Worst faces listed in the summary")->capture_default_str();
  cmd->add_flag("--overwrite", a->overwrite, "Replace existing output files");
  cmd->add_flag("--quiet", a->quiet, "No progress output");
  cmd->callback([a]() {
    a->options.measure = parse_measure(a->measure);
    a->options.check();
    io::check_can_write(a->out, a->overwrite);
    if (!a->json.empty()) io::check_can_write(a->json, a->overwrite);
    const Scene scene = a->input.read();
    ProgressBar bar(a->quiet);
    const PriResult r = compute_pri(scene, a->options, bar.callback());
    bar.finish();
    io::PlyWriteOptions ply;
    ply.overwrite = a->overwrite;
    io::write_ply(mesh_with_pri(scene.mesh, r), a->out, ply);
    const std::string summary = pri_summary_json(r, a->options, a->worst);
    if (!a->json.empty())
      io::write_atomically(a->json, [&](std::ostream& out) { out << summary; }, a->overwrite);
    const PriSummary s = summarize_pri(r, 1);
    std::cout << "faces " << s.faces << ": " << s.observed << " observed, " << s.unobserved
              << " unobserved, " << s.textureless << " textureless; " << r.views_used
              << " views; " << r.seconds << " s\n";
    if (!s.percentiles.empty())
      std::cout << "PRI (" << a->measure << ") median " << s.percentiles[3].second << ", 95% "
                << s.percentiles[5].second << ", worst face " << s.worst[0].face << " ("
                << s.worst[0].pri << ")\n";
    std::cout << "mesh with PRI: " << a->out << "\n";
    if (!a->json.empty()) std::cout << "summary: " << a->json << "\n";
  });
}

}  // namespace meshnbv::cli
