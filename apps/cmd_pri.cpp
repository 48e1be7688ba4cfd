// meshnbv pri: per-face Photo-consistency Reconstruction Index.
#include <iostream>
#include <memory>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/pri_io.h"
#include "meshnbv/results.h"
#include "meshnbv/options.h"
#include "meshnbv/pri.h"
#include "progress_bar.h"

namespace meshnbv::cli {

void add_pri_options(CLI::App* cmd, OptionFlags* flags, PriOptions* options) {
  flags->add(cmd, pri_option_table(), options);
}

void finish_options(const OptionFlags& flags, PriOptions* pri, SuggestOptions* suggest) {
  flags.apply();
  pri->check();
  if (suggest) suggest->check();
}

void ProgressChoice::add_to(CLI::App* cmd) {
  cmd->add_option("--progress", mode, "Progress on stderr: a bar, JSON lines, or none")
      ->check(CLI::IsMember({"bar", "json", "none"}))
      ->capture_default_str();
  cmd->add_flag("--quiet", quiet, "No progress output (--progress none)");
}

void add_pri_command(CLI::App& app) {
  struct Args {
    SceneInput input;
    PriOptions options;
    OptionFlags flags;
    ProgressChoice progress;
    std::string out, json, previous;
    std::size_t summary_worst = 10;
    bool overwrite = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "pri", "Per-face Photo-consistency Reconstruction Index: which faces are poorly "
             "reconstructed (higher = worse)");
  a->input.add_to(cmd);
  add_pri_options(cmd, &a->flags, &a->options);
  cmd->add_option("--out", a->out,
                  "PLY with per-face quality = PRI (NaN where unobserved), pri_views and colour "
                  "(green best, red worst, grey unobserved)")
      ->required();
  cmd->add_option("--json", a->json, "Summary as JSON");
  cmd->add_option("--previous", a->previous,
                  "Incremental PRI: a PLY written by meshnbv pri for an earlier mesh or view set; "
                  "only the faces whose geometry, visible views, cameras, images or options "
                  "changed are computed again (the result equals a full computation)");
  cmd->add_option("--summary-worst", a->summary_worst, "Worst faces listed in the JSON summary")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->add_flag("--overwrite", a->overwrite, "Replace existing output files");
  a->progress.add_to(cmd);
  cmd->callback([a]() {
    finish_options(a->flags, &a->options);
    io::check_can_write(a->out, a->overwrite);
    if (!a->json.empty()) io::check_can_write(a->json, a->overwrite);
    const Scene scene = a->input.read();
    std::unique_ptr<PriPrevious> previous;
    if (!a->previous.empty()) previous = std::make_unique<PriPrevious>(io::read_pri_previous(a->previous));
    ProgressBar bar(a->progress.silent(), a->progress.json());
    const PriResult r = scene_pri(scene, a->options, bar.callback(), previous.get());
    bar.finish();
    io::PlyWriteOptions ply;
    ply.overwrite = a->overwrite;
    ply.exact_coordinates = true;
    ply.comments = pri_key_comments(r);  // the very mesh, for --previous
    io::write_ply(mesh_with_pri(scene.mesh, r), a->out, ply);
    const std::string summary = pri_summary_json(r, a->options, a->summary_worst);
    if (!a->json.empty())
      io::write_atomically(a->json, [&](std::ostream& out) { out << summary; }, a->overwrite);
    const PriSummary s = summarize_pri(r, 1);
    std::cout << "faces " << s.faces << ": " << s.observed << " observed, " << s.unobserved
              << " unobserved, " << s.textureless << " textureless; " << r.views_used
              << " views; " << r.seconds << " s\n";
    if (r.views_reduced > 0)
      std::cout << "photos: " << r.views_reduced << " of " << r.views_used
                << " JPEGs decoded smaller, their faces' lattices being coarser than their pixels "
                   "(max_image_reduction "
                << a->options.max_image_reduction << ")\n";
    if (previous)
      std::cout << "incremental: recomputed " << r.recomputed << " of " << s.faces << " faces, reused "
                << s.faces - r.recomputed << " from " << a->previous << "; views selected again for "
                << r.reselected << " faces\n";
    if (!s.percentiles.empty()) {
      std::cout << "PRI (" << measure_name(a->options.measure) << ", " << measure_unit(a->options.measure)
                << ") median " << s.percentiles[3].second << ", 95% " << s.percentiles[5].second
                << ", worst face " << s.worst[0].face << " (" << s.worst[0].pri << ")\n";
      const PriEvidence e = pri_evidence(r);
      std::cout << "evidence: " << e.two_views << " of " << e.observed << " observed faces rest on 2 views; "
                << e.low_texture << " on low texture (below " << e.low_texture_below << ")\n";
    }
    std::cout << "mesh with PRI: " << a->out << "\n";
    if (!a->json.empty()) std::cout << "summary: " << a->json << "\n";
  });
}

}  // namespace meshnbv::cli
