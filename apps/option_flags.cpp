#include "option_flags.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include "meshnbv/error.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv::cli {
namespace {

std::string type_label(OptionType type, const std::vector<std::string>& choices) {
  switch (type) {
    case OptionType::Int: return "INT";
    case OptionType::Real: return "REAL";
    case OptionType::Choice: {
      std::string out;
      for (const auto& c : choices) out += (out.empty() ? "" : "|") + c;
      return out;
    }
    case OptionType::Bool: return "";
  }
  return "";
}

// The whole text as a number; strtod/strtoll accept nan and inf, which the
// range check then reports.
OptionValue parse_number(const std::string& name, OptionType type, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  if (type == OptionType::Int) {
    const long long x = std::strtoll(begin, &end, 10);
    if (!text.empty() && *end == '\0' && errno != ERANGE) return std::int64_t(x);
    // "1e3", "2.0": a whole number written as a real is accepted by set().
  }
  errno = 0;
  const double d = std::strtod(begin, &end);
  if (text.empty() || *end != '\0')
    throw Error(cli_flag(name) + ": '" + text + "' is not a number");
  return d;
}

}  // namespace

OptionFlags::Flag* OptionFlags::find(const std::string& name) {
  for (auto& f : flags_)
    if (f->name == name) return f.get();
  return nullptr;
}

template <class Options>
void OptionFlags::add(CLI::App* cmd, const OptionTable<Options>& table, Options* target,
                      const std::vector<std::string>& except) {
  for (const OptionSpec<Options>& spec : table) {
    if (std::find(except.begin(), except.end(), spec.name) != except.end()) continue;
    Flag* flag = find(spec.name);
    if (!flag) {
      flags_.push_back(std::make_unique<Flag>());
      flag = flags_.back().get();
      flag->name = spec.name;
      flag->type = spec.type;
      const std::string def = option_value_text(spec.default_value());
      std::string help = spec.help;
      if (spec.type == OptionType::Int || spec.type == OptionType::Real)
        help += "; " + spec.range.describe();
      if (spec.type == OptionType::Bool) {
        const std::string names = cli_flag(spec.name) + ",!--no-" + cli_flag(spec.name).substr(2);
        flag->option = cmd->add_flag(names, *flag->flag, help)->default_str(def);
      } else {
        flag->option = cmd->add_option(cli_flag(spec.name), *flag->text, help)
                           ->type_name(type_label(spec.type, spec.choices))
                           ->default_str(def);
      }
    }
    // Set, then check at once, so that the error names the flag as typed.
    flag->setters.push_back([&spec, target](const OptionValue& v) {
      std::string problem;
      try {
        spec.set(*target, v);
        problem = spec.problem(spec.get(*target));
      } catch (const Error& e) {
        problem = e.reason();
      }
      if (!problem.empty()) {
        if (problem.compare(0, spec.name.size(), spec.name) == 0)
          problem = cli_flag(spec.name) + problem.substr(spec.name.size());
        throw Error(problem);
      }
    });
  }
}

void OptionFlags::apply() const {
  for (const auto& f : flags_) {
    if (f->option->count() == 0) continue;
    OptionValue value;
    if (f->type == OptionType::Bool)
      value = *f->flag;
    else if (f->type == OptionType::Choice)
      value = *f->text;
    else
      value = parse_number(f->name, f->type, *f->text);
    for (const auto& set : f->setters) set(value);
  }
}

template void OptionFlags::add(CLI::App*, const OptionTable<PriOptions>&, PriOptions*,
                               const std::vector<std::string>&);
template void OptionFlags::add(CLI::App*, const OptionTable<MissionOptions>&, MissionOptions*,
                               const std::vector<std::string>&);
template void OptionFlags::add(CLI::App*, const OptionTable<SuggestOptions>&, SuggestOptions*,
                               const std::vector<std::string>&);

}  // namespace meshnbv::cli
