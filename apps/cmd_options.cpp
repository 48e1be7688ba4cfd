// meshnbv options: the option tables of the core, with every front end's
// spelling (docs/options.md is generated from it).
#include <iostream>
#include <memory>

#include "commands.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/options.h"

namespace meshnbv::cli {
namespace {

template <class Options>
void print_markdown(std::ostream& out, const char* title, const OptionTable<Options>& table) {
  out << "### " << title << "\n\n"
      << "| name (JSON, MeshLab) | command line | VTK property | type | default | range | "
         "meaning |\n|---|---|---|---|---|---|---|\n";
  for (const auto& s : table) {
    std::string range;
    if (s.type == OptionType::Int || s.type == OptionType::Real) range = s.range.describe();
    if (s.type == OptionType::Choice)
      for (const auto& c : s.choices) range += (range.empty() ? "" : ", ") + c;
    if (s.type == OptionType::Bool) range = "true, false";
    std::string flag = cli_flag(s.name);
    if (s.type == OptionType::Bool) flag += "`, `--no-" + flag.substr(2);
    out << "| `" << s.name << "` | `" << flag << "` | `" << vtk_name(s.name) << "` | "
        << option_type_name(s.type) << " | " << option_value_text(s.default_value()) << " | "
        << range << " | " << s.help << " |\n";
  }
  out << "\n";
}

}  // namespace

void add_options_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "options", "Every option of PRI and of the next-view suggestion, with its name in each "
                 "front end (command line, VTK, MeshLab, JSON), default and range");
  cmd->add_flag("--json", *json, "As JSON (the tables the front ends are derived from)");
  cmd->callback([json]() {
    if (*json) {
      std::cout << option_tables_json();
      return;
    }
    print_markdown(std::cout, "PRI (`meshnbv pri`, `run`, `suggest`, `loop`; vtkMeshNBVPRIFilter; "
                              "MeshLab Compute PRI)",
                   pri_option_table());
    print_markdown(std::cout, "Next-view suggestion (`meshnbv suggest`, `run`, `loop`; "
                              "vtkMeshNBVNextBestViewFilter; MeshLab Suggest Next View)",
                   suggest_option_table());
    print_markdown(std::cout, "Drone missions (`meshnbv mission`)", mission_option_table());
  });
}

}  // namespace meshnbv::cli
