// Command-line flags derived from the core's option tables (options.h): one
// flag per option, named cli_flag(name), with the table's default and range
// in its help. Booleans are --name / --no-name. An option held by two
// tables (threads) is one flag that sets both.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "meshnbv/options.h"

namespace meshnbv::cli {

class OptionFlags {
 public:
  // Adds every option of `table` to `cmd`; after parsing, apply() writes the
  // flags that were given into `*target` (which must outlive this object).
  // Options named in `except` are left out (a command that sets them itself).
  template <class Options>
  void add(CLI::App* cmd, const OptionTable<Options>& table, Options* target,
           const std::vector<std::string>& except = {});
  // Sets the given flags on their structs; throws Error naming the option
  // for a value that does not parse or is out of range.
  void apply() const;

 private:
  struct Flag {
    std::string name;
    OptionType type;
    CLI::Option* option = nullptr;
    std::shared_ptr<std::string> text = std::make_shared<std::string>();
    std::shared_ptr<bool> flag = std::make_shared<bool>(false);
    // One setter per struct that holds the option.
    std::vector<std::function<void(const OptionValue&)>> setters;
  };
  Flag* find(const std::string& name);
  std::vector<std::unique_ptr<Flag>> flags_;
};

}  // namespace meshnbv::cli
