// meshnbv: command line front end of the MeshNBV core.
#include <CLI/CLI.hpp>

#include <iostream>

#include "commands.h"
#include "meshnbv/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "MeshNBV: find the poorly reconstructed parts of a mesh from its calibrated photos, and "
      "where to take the next photo (Morreale, Romanoni, Matteucci 2018)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "meshnbv 0.1.0");
  meshnbv::cli::add_info_command(app);
  meshnbv::cli::add_convert_command(app);
  meshnbv::cli::add_synth_command(app);
  meshnbv::cli::add_pri_command(app);
  meshnbv::cli::add_suggest_command(app);
  meshnbv::cli::add_run_command(app);
  meshnbv::cli::add_loop_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const meshnbv::Error& e) {
    std::cerr << "meshnbv: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
