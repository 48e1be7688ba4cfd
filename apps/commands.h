#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "meshnbv/io/scene_io.h"
#include "meshnbv/mission/scene_mission.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"
#include "option_flags.h"

namespace meshnbv::cli {

// Options every command that reads a scene shares (same names everywhere).
struct SceneInput {
  std::string path;
  std::string format = "auto";
  std::string mesh;
  std::string image_dir;
  // Print the reader's warnings (images not found, mesh in another frame,
  // ...) to stderr; `info` prints them itself.
  bool print_warnings = true;
  void add_to(CLI::App* cmd);
  Scene read() const;
};

// Before any work: the folder of a COLMAP text model can be written, and
// its files do not exist unless `overwrite` (io::check_can_write_folder,
// io::check_can_write). Throws Error otherwise.
void check_colmap_output(const std::string& folder, bool overwrite);

// The inputs of a drone mission as flags, shared by `mission` and `run`:
// --georef, --takeoff, --takeoff-wgs84, --keep-out, --keep-out-box and the
// mission option table (through `flags`, applied by the caller).
struct MissionFlags {
  MissionOptions options;
  std::string georef, takeoff, takeoff_wgs84, keep_out;
  std::vector<std::string> boxes;
  void add_to(CLI::App* cmd, OptionFlags* flags);
  // After flags->apply(): the request, keep-out files read. Throws Error.
  mission::MissionRequest request() const;
};

// The command line program: every command, one-line errors ("<program>:
// error: ..."), exit code 0 or 1.
int run_main(int argc, char** argv, const std::string& program);

// How the commands compute PRI: compute_pri (meshnbv), or the engine set
// before run_main (meshnbv-mpi: tiles over MPI ranks, the same result).
using PriEngine = std::function<PriResult(const Scene&, const PriOptions&, const ProgressCallback&,
                                          const PriPrevious*)>;
void set_pri_engine(PriEngine engine);
PriResult scene_pri(const Scene& scene, const PriOptions& options, const ProgressCallback& progress,
                    const PriPrevious* previous = nullptr);
// How the commands score candidate poses (suggest_views): empty = here,
// or the scorer set before run_main (meshnbv-mpi: over its ranks).
void set_candidate_scorer(CandidateScorer scorer);
const CandidateScorer& candidate_scorer();

// Subcommands run their work in a callback and throw meshnbv::Error on failure.
void add_info_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_pri_command(CLI::App& app);
void add_suggest_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_loop_command(CLI::App& app);
void add_mission_command(CLI::App& app);
void add_options_command(CLI::App& app);
// The PRI and next-view options as flags, derived from the core's option
// tables (options.h) through `flags`; after parsing, finish_options()
// applies them (one --threads sets both) and checks both structs.
void add_pri_options(CLI::App* cmd, OptionFlags* flags, PriOptions* options);
void add_suggest_options(CLI::App* cmd, OptionFlags* flags, SuggestOptions* options);
void finish_options(const OptionFlags& flags, PriOptions* pri, SuggestOptions* suggest = nullptr);
// --progress bar|json|none (bar by default; --quiet = none), shared by the
// commands that run long.
struct ProgressChoice {
  std::string mode = "bar";
  bool quiet = false;
  void add_to(CLI::App* cmd);
  bool silent() const { return quiet || mode == "none"; }
  bool json() const { return !quiet && mode == "json"; }
};

}  // namespace meshnbv::cli
