// meshnbv: command line front end of the MeshNBV core.
#include <CLI/CLI.hpp>

#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>

#include "commands.h"
#include "meshnbv/error.h"

namespace {

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
  std::cerr << "meshnbv: error: " << (line.empty() ? "unknown error" : line) << std::endl;
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "MeshNBV: find the poorly reconstructed parts of a mesh from its calibrated photos, and "
      "where to take the next photo (Morreale, Romanoni, Matteucci 2018)."};
  try {
    app.require_subcommand(1);
    app.set_version_flag("--version", "meshnbv 0.1.0");
    meshnbv::cli::add_info_command(app);
    meshnbv::cli::add_convert_command(app);
    meshnbv::cli::add_synth_command(app);
    meshnbv::cli::add_pri_command(app);
    meshnbv::cli::add_suggest_command(app);
    meshnbv::cli::add_run_command(app);
    meshnbv::cli::add_loop_command(app);
    meshnbv::cli::add_mission_command(app);
    meshnbv::cli::add_options_command(app);
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
