#pragma once

#include <CLI/CLI.hpp>

#include "meshnbv/io/scene_io.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv::cli {

// Options every command that reads a scene shares (same names everywhere).
struct SceneInput {
  std::string path;
  std::string format = "auto";
  std::string mesh;
  std::string image_dir;
  void add_to(CLI::App* cmd);
  Scene read() const;
};

// Before any work: the folder of a COLMAP text model can be written, and
// its files do not exist unless `overwrite` (io::check_can_write_folder,
// io::check_can_write). Throws Error otherwise.
void check_colmap_output(const std::string& folder, bool overwrite);

// Subcommands run their work in a callback and throw meshnbv::Error on failure.
void add_info_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_pri_command(CLI::App& app);
void add_suggest_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_loop_command(CLI::App& app);
// The next-view options as flags, shared by suggest and run.
void add_suggest_options(CLI::App* cmd, SuggestOptions* options, std::string* mode, std::string* weights);
// "m1,m2,m3,m4" -> four numbers; throws Error otherwise.
std::array<double, 4> parse_weights(const std::string& text);
// Applies the options given as text (measure, candidate mode, weights),
// shares the thread count, and checks both option sets.
void finish_options(PriOptions* pri, const std::string& measure, SuggestOptions* suggest,
                    const std::string& mode, const std::string& weights);
// The PRI options as flags, shared by every command that computes PRI.
void add_pri_options(CLI::App* cmd, PriOptions* options, std::string* measure);

}  // namespace meshnbv::cli
