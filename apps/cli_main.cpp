// The command line front end of the MeshNBV core: the commands, one-line
// errors and exit codes of meshnbv and meshnbv-mpi (run_main).
#include <CLI/CLI.hpp>

#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>

#include "commands.h"
#include "meshnbv/error.h"

namespace meshnbv::cli {

namespace {

PriEngine& engine() {
  static PriEngine e;
  return e;
}

CandidateScorer& scorer() {
  static CandidateScorer s;
  return s;
}

std::string& program_name() {
  static std::string name = "meshnbv";
  return name;
}

// Every failure ends the same way: one line on stderr, exit code 1. Line
// breaks inside a message (CLI11 lists several problems on several lines)
// become "; ".
int fail(const std::string& message) {
  std::string line;
  bool pending_break = false;
  for (char c : message) {
    if (c == '\n' || c == '\r') {
      pending_break = !line.empty();
      continue;
    }
    if (pending_break) {
      line += "; ";
      pending_break = false;
    }
    line += c;
  }
  std::cerr << program_name() << ": error: " << (line.empty() ? "unknown error" : line) << std::endl;
  return 1;
}

}  // namespace

void set_pri_engine(PriEngine e) { engine() = std::move(e); }
void set_candidate_scorer(CandidateScorer s) { scorer() = std::move(s); }
const CandidateScorer& candidate_scorer() { return scorer(); }

PriResult scene_pri(const Scene& scene, const PriOptions& options, const ProgressCallback& progress,
                    const PriPrevious* previous) {
  if (engine()) return engine()(scene, options, progress, previous);
  return compute_pri(scene, options, progress, previous);
}

int run_main(int argc, char** argv, const std::string& program) {
  program_name() = program;
  CLI::App app{
      "MeshNBV: find the poorly reconstructed parts of a mesh from its calibrated photos, and "
      "where to take the next photo (Morreale, Romanoni, Matteucci 2018)."};
  try {
    app.require_subcommand(1);
    app.set_version_flag("--version", program + " 0.1.0");
    add_info_command(app);
    add_convert_command(app);
    add_synth_command(app);
    add_pri_command(app);
    add_suggest_command(app);
    add_run_command(app);
    add_loop_command(app);
    add_mission_command(app);
    add_options_command(app);
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version (CallForHelp, CallForVersion)
  } catch (const CLI::RequiredError& e) {
    // "A subcommand is required" and missing options: say where help is.
    return fail(std::string(e.what()) + " (run with --help)");
  } catch (const CLI::ParseError& e) {
    return fail(std::string(e.what()) + " (run with --help)");
  } catch (const meshnbv::Error& e) {  // includes Cancelled
    return fail(e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    return fail(e.what());
  } catch (const std::bad_alloc&) {
    return fail("out of memory");
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what());
  } catch (...) {
    return fail("internal error: unknown exception");
  }
  return 0;
}

}  // namespace meshnbv::cli
