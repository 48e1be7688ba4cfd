// The option tables: one per options struct that users set (PriOptions,
// SuggestOptions, eval::LoopOptions), each entry with the option's name,
// type, default (the struct's own), accepted range or words, and help. Every
// front end derives its options from these tables, so that a name, default
// or range cannot drift between them (docs/options.md):
//
//   name (snake_case)      JSON key, MeshLab parameter      samples_per_side
//   cli_flag(name)         command line                     --samples-per-side
//   vtk_name(name)         VTK/ParaView property (Set/Get)  SamplesPerSide
//
// Booleans are flags everywhere on the command line: --name turns an option
// on, --no-name off. check_options() is the structs' check() for the table's
// fields; errors name the option and its range in one line.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace meshnbv {

enum class OptionType { Bool, Int, Real, Choice };
std::string option_type_name(OptionType type);  // bool | int | real | choice

// Accepted numbers: [min, max] (an end is open where said), plus listed
// special values with their meaning (0 = automatic, ...).
struct OptionRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false, max_open = false;
  std::vector<std::pair<double, std::string>> specials;  // (value, meaning)
  std::string unit;  // "degrees", "pixels", or empty

  bool contains(double value) const;  // false for NaN
  // "0 (automatic) or in [2, 64]", "in (0, 90] degrees", "any finite number"
  std::string describe() const;
};

// A value of any option type: Bool, Int (std::int64_t), Real, Choice (the word).
using OptionValue = std::variant<bool, std::int64_t, double, std::string>;
// "true", "12", "0.5", "ssd": the shortest text that reads back.
std::string option_value_text(const OptionValue& value);

template <class Options>
struct OptionSpec {
  std::string name;   // snake_case
  OptionType type;
  std::string label;  // a few words for dialogs: "Samples per side"
  std::string help;   // what it does, unit included (tooltips, --help, docs)
  OptionRange range;                 // Int, Real
  std::vector<std::string> choices;  // Choice
  std::function<OptionValue(const Options&)> get;
  // Takes a value of the option's type (an Int also from a Real with an
  // integral value, a Choice only from one of its words); throws Error
  // otherwise. Does not check the range: check_options() does.
  std::function<void(Options&, const OptionValue&)> set;

  OptionValue default_value() const { return get(Options{}); }
  // "samples_per_side must be 0 (automatic) or in [2, 64], got 1000", or
  // empty when `value` is accepted.
  std::string problem(const OptionValue& value) const;
};

template <class Options>
using OptionTable = std::vector<OptionSpec<Options>>;

struct PriOptions;
struct SuggestOptions;
struct MissionOptions;
const OptionTable<PriOptions>& pri_option_table();
const OptionTable<SuggestOptions>& suggest_option_table();
const OptionTable<MissionOptions>& mission_option_table();  // meshnbv mission

// Throws Error for the first option of `options` out of its range.
template <class Options>
void check_options(const Options& options, const OptionTable<Options>& table);

// "samples_per_side" -> "--samples-per-side"
std::string cli_flag(const std::string& name);
// "samples_per_side" -> "SamplesPerSide"
std::string vtk_name(const std::string& name);

// The table's options of `options` as a JSON object, {"name": value, ...},
// in table order.
template <class Options>
std::string options_json(const Options& options, const OptionTable<Options>& table);
// Sets the options named in a JSON object (text); unknown keys, wrong types
// and values out of range are errors naming the key.
template <class Options>
void parse_options_json(const std::string& text, const OptionTable<Options>& table, Options* options);

// Every table with every front end's spelling, default, range and help, as
// JSON: {"pri": [{"name", "cli", "vtk", "meshlab", "type", "default",
// "range", "min", "max", "choices", "help"}, ...], "suggest": [...]}.
// `meshnbv options --json` prints it; the front-end test compares it with
// what each front end really offers.
std::string option_tables_json();

}  // namespace meshnbv
