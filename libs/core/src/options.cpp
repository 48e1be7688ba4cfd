// The option tables of PriOptions and SuggestOptions (options.h), and what
// every front end derives from them.
#include "meshnbv/options.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv {

std::string option_type_name(OptionType type) {
  switch (type) {
    case OptionType::Bool: return "bool";
    case OptionType::Int: return "int";
    case OptionType::Real: return "real";
    case OptionType::Choice: return "choice";
  }
  return "real";
}

bool OptionRange::contains(double value) const {
  for (const auto& [special, meaning] : specials)
    if (value == special) return true;
  if (std::isnan(value)) return false;
  const bool above = min_open ? value > min : value >= min;
  const bool below = max_open ? value < max : value <= max;
  return above && below && std::isfinite(value);
}

std::string OptionRange::describe() const {
  std::string out;
  const std::string in_unit = unit.empty() ? "" : " " + unit;
  for (const auto& [special, meaning] : specials)
    out += format_option_value(special) + " (" + meaning + ") or ";
  if (std::isinf(min) && std::isinf(max)) return out + "any finite number" + in_unit;
  if (std::isinf(max)) return out + (min_open ? "> " : ">= ") + format_option_value(min) + in_unit;
  if (std::isinf(min)) return out + (max_open ? "< " : "<= ") + format_option_value(max) + in_unit;
  return out + "in " + (min_open ? "(" : "[") + format_option_value(min) + ", " +
         format_option_value(max) + (max_open ? ")" : "]") + in_unit;
}

std::string option_value_text(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const auto* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return format_option_value(*d);
  return std::get<std::string>(value);
}

namespace {
// "a, b or c"
std::string join_choices(const std::vector<std::string>& choices) {
  std::string out;
  for (std::size_t i = 0; i < choices.size(); ++i)
    out += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
  return out;
}
}  // namespace

template <class Options>
std::string OptionSpec<Options>::problem(const OptionValue& value) const {
  switch (type) {
    case OptionType::Bool: return {};
    case OptionType::Choice: {
      const std::string& word = std::get<std::string>(value);
      for (const std::string& c : choices)
        if (c == word) return {};
      return name + " must be " + join_choices(choices) + ", got '" + word + "'";
    }
    case OptionType::Int:
    case OptionType::Real: {
      const double x = type == OptionType::Int ? double(std::get<std::int64_t>(value))
                                               : std::get<double>(value);
      if (range.contains(x)) return {};
      return name + " must be " + range.describe() + ", got " + option_value_text(value);
    }
  }
  return {};
}

template <class Options>
void check_options(const Options& options, const OptionTable<Options>& table) {
  for (const auto& spec : table) {
    const std::string problem = spec.problem(spec.get(options));
    if (!problem.empty()) throw Error(problem);
  }
}

namespace {

// Typed accessors for the table entries below.
bool as_bool(const std::string& name, const OptionValue& v) {
  if (const bool* b = std::get_if<bool>(&v)) return *b;
  throw Error(name + " takes true or false, got " + option_value_text(v));
}

std::int64_t as_int(const std::string& name, const OptionValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return *i;
  if (const double* d = std::get_if<double>(&v)) {
    // Integral doubles only, within the range that converts exactly.
    if (std::isfinite(*d) && std::floor(*d) == *d && std::fabs(*d) < 9.0e15)
      return std::int64_t(*d);
  }
  throw Error(name + " takes a whole number, got " + option_value_text(v));
}

double as_real(const std::string& name, const OptionValue& v) {
  if (const double* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return double(*i);
  throw Error(name + " takes a number, got " + option_value_text(v));
}

std::string as_word(const std::string& name, const OptionValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  throw Error(name + " takes a word, got " + option_value_text(v));
}

// An int field stored as int: values beyond int's range are kept as the
// nearest int's neighbour outside the option's range, so check_options()
// reports them instead of a silent wrap-around.
int clamp_to_int(std::int64_t x) {
  if (x > std::numeric_limits<int>::max()) return std::numeric_limits<int>::max();
  if (x < std::numeric_limits<int>::min()) return std::numeric_limits<int>::min();
  return int(x);
}

template <class O>
OptionSpec<O> bool_option(std::string name, std::string label, std::string help, bool O::*field) {
  OptionSpec<O> s{name, OptionType::Bool, std::move(label), std::move(help), {}, {}, {}, {}};
  s.get = [field](const O& o) { return OptionValue(o.*field); };
  s.set = [field, name](O& o, const OptionValue& v) { o.*field = as_bool(name, v); };
  return s;
}

template <class O, class Get, class Set>
OptionSpec<O> int_option(std::string name, std::string label, std::string help, OptionRange range,
                             Get get, Set set) {
  OptionSpec<O> s{name, OptionType::Int, std::move(label), std::move(help), std::move(range), {}, {}, {}};
  s.get = [get](const O& o) { return OptionValue(std::int64_t(get(o))); };
  s.set = [set, name](O& o, const OptionValue& v) { set(o, as_int(name, v)); };
  return s;
}

template <class O, class Get, class Set>
OptionSpec<O> real_option(std::string name, std::string label, std::string help, OptionRange range,
                             Get get, Set set) {
  OptionSpec<O> s{name, OptionType::Real, std::move(label), std::move(help), std::move(range), {}, {}, {}};
  s.get = [get](const O& o) { return OptionValue(double(get(o))); };
  s.set = [set, name](O& o, const OptionValue& v) { set(o, as_real(name, v)); };
  return s;
}

template <class O, class Get, class Set>
OptionSpec<O> choice_option(std::string name, std::string label, std::string help,
                            std::vector<std::string> choices, Get get, Set set) {
  OptionSpec<O> s{name, OptionType::Choice, std::move(label), std::move(help), {}, std::move(choices), {}, {}};
  s.get = [get](const O& o) { return OptionValue(get(o)); };
  s.set = [set, name, words = s.choices](O& o, const OptionValue& v) {
    const std::string word = as_word(name, v);
    if (std::find(words.begin(), words.end(), word) == words.end())
      throw Error(name + " must be " + join_choices(words) + ", got '" + word + "'");
    set(o, word);
  };
  return s;
}

OptionRange closed(double lo, double hi, std::string unit = {}) {
  return OptionRange{lo, hi, false, false, {}, std::move(unit)};
}
OptionRange left_open(double lo, double hi, std::string unit = {}) {
  return OptionRange{lo, hi, true, false, {}, std::move(unit)};
}
OptionRange with_special(OptionRange r, double value, std::string meaning) {
  r.specials.emplace_back(value, std::move(meaning));
  return r;
}

// Both tables hold `threads`, with the same meaning and range; commands that
// use both register it once.
const char* kThreadsHelp = "Worker threads (0 = all cores); results do not depend on it";
OptionRange threads_range() { return with_special(closed(1, 1024), 0, "all cores"); }

}  // namespace

const OptionTable<PriOptions>& pri_option_table() {
  using O = PriOptions;
  static const OptionTable<O> table = {
      choice_option<O>(
          "measure", "Measure",
          "What PRI measures. ssd: mean squared difference of the samples of every pair of views "
          "(the paper's choice); ncc: (1 - normalised cross-correlation) / 2 of every pair, "
          "insensitive to contrast, pairs with a textureless patch skipped; offset: the distance "
          "along the face's normal (scene units) to where its views agree best, found by "
          "sweeping offsets of a support patch around the face (an estimate of the face's error)",
          {"ssd", "ncc", "offset"}, [](const O& o) { return measure_name(o.measure); },
          [](O& o, const std::string& w) { o.measure = parse_measure(w); }),
      int_option<O>(
          "samples_per_side", "Samples per side",
          "Subdivisions r of the barycentric lattice on each face ((r+1)(r+2)/2 samples); 0 = "
          "automatic: the largest projected edge in pixels, clamped to [2, 32]",
          with_special(closed(2, 64), 0, "automatic"), [](const O& o) { return o.samples_per_side; },
          [](O& o, std::int64_t x) { o.samples_per_side = clamp_to_int(x); }),
      int_option<O>(
          "max_views_per_face", "Max views per face",
          "Views compared per face, those with the smallest incidence angle first (0 = all views "
          "that see the face)",
          with_special(closed(2, std::numeric_limits<double>::infinity()), 0, "all"), [](const O& o) { return o.max_views_per_face; },
          [](O& o, std::int64_t x) { o.max_views_per_face = clamp_to_int(x); }),
      real_option<O>(
          "max_incidence_angle", "Max incidence angle",
          "Degrees. A view whose direction makes a larger angle with the face normal does not "
          "count as seeing the face (grazing views give slivers); 90 = the plain back-face rule",
          left_open(0, 90, "degrees"), [](const O& o) { return o.max_incidence_angle; },
          [](O& o, double x) { o.max_incidence_angle = x; }),
      int_option<O>(
          "max_image_reduction", "Max image reduction",
          "A JPEG photo may be decoded 2, 4 or 8 times smaller on each side (the largest power of "
          "two up to this) when every face that may use it has its sampling lattice at least that "
          "many pixels apart there (the decoder's DCT scaling): faster and less memory, but the "
          "averaged pixels lose fine texture and PRI finds error less well; 1 = always at full "
          "resolution",
          closed(1, 8), [](const O& o) { return o.max_image_reduction; },
          [](O& o, std::int64_t x) { o.max_image_reduction = clamp_to_int(x); }),
      real_option<O>(
          "edge_margin", "Edge margin",
          "Pixels. The sampling lattice is contracted towards the face's centroid so that it "
          "stays this far inside the face in every view (samples on the border read the pixels "
          "beyond it); 0 = sample the whole face",
          closed(0, 16, "pixels"), [](const O& o) { return o.edge_margin; },
          [](O& o, double x) { o.edge_margin = x; }),
      real_option<O>(
          "support_radius", "Support radius",
          "Pixels. offset: each face's signed offset is averaged over the connected faces within "
          "2 sigma, Gaussian-weighted with sigma this many pixels of its reference view",
          closed(0.5, 32, "pixels"), [](const O& o) { return o.support_radius; },
          [](O& o, double x) { o.support_radius = x; }),
      real_option<O>(
          "offset_range", "Offset range",
          "Pixels. offset: offsets along the normal are swept up to this disparity, in the view "
          "where an offset moves the face most, on both sides of the face",
          closed(0.25, 64, "pixels"), [](const O& o) { return o.offset_range; },
          [](O& o, double x) { o.offset_range = x; }),
      int_option<O>(
          "offset_steps", "Offset steps",
          "offset: hypotheses on each side of the face (2 x this + 1 in all), hypothesis j at "
          "offset_range x (j / offset_steps)^1.5: finer near the face, coarser towards the range",
          closed(1, 32), [](const O& o) { return o.offset_steps; },
          [](O& o, std::int64_t x) { o.offset_steps = clamp_to_int(x); }),
      bool_option<O>("check_interior_occlusion", "Check interior occlusion",
                     "Besides its three vertices, the face's centroid and edge midpoints must be "
                     "unoccluded in a view (catches partial occlusion, e.g. behind a parapet)",
                     &O::check_interior_occlusion),
      bool_option<O>("color", "Compare colour", "Compare R, G, B samples instead of luminance",
                     &O::color),
      real_option<O>(
          "textureless_variance", "Textureless variance",
          "ncc: a patch whose samples (in [0, 1]) vary less than this is textureless, and its "
          "pairs are skipped",
          closed(0, 1), [](const O& o) { return o.textureless_variance; },
          [](O& o, double x) { o.textureless_variance = x; }),
      int_option<O>(
          "threads", "Threads", kThreadsHelp, threads_range(), [](const O& o) { return o.threads; },
          [](O& o, std::int64_t x) { o.threads = clamp_to_int(x); }),
  };
  return table;
}

const OptionTable<SuggestOptions>& suggest_option_table() {
  using O = SuggestOptions;
  auto weight = [](const char* name, const char* label, const char* term, std::size_t k) {
    return real_option<O>(
        name, label,
        std::string("Weight m") + std::to_string(k + 1) + " of the " + term + " term of the energy",
        closed(0, 1000), [k](const O& o) { return o.energy.weights[k]; },
        [k](O& o, double x) { o.energy.weights[k] = x; });
  };
  static const OptionTable<O> table = {
      choice_option<O>(
          "candidates", "Candidates",
          "Where candidate poses come from. given: the views without an image (or marked "
          "unused, or another scene's), all ranked; sampled: a Fibonacci spiral of directions on "
          "the hemisphere of the worst region's mean normal, at 0.75, 1 and 1.5 times the median "
          "viewing distance, looking at the region; refined: the best sampled poses improved by "
          "Nelder-Mead over position and viewing direction",
          {"given", "sampled", "refined"}, [](const O& o) { return candidate_mode_name(o.mode); },
          [](O& o, const std::string& w) { o.mode = parse_candidate_mode(w); }),
      int_option<O>(
          "top", "Suggestions",
          "Number of suggestions, chosen greedily: each pick counts as an existing view for the "
          "next ones",
          closed(1, 100), [](const O& o) { return o.top; },
          [](O& o, std::int64_t x) { o.top = clamp_to_int(x); }),
      int_option<O>(
          "worst_faces", "Worst faces (K)",
          "The K observed faces with the highest PRI form the worst region whose vertices the "
          "energy scores",
          closed(1, 10000), [](const O& o) { return o.worst_k; },
          [](O& o, std::int64_t x) { o.worst_k = clamp_to_int(x); }),
      choice_option<O>(
          "energy", "Energy",
          "What a candidate is scored by. paper: the SPEC's energy (occlusion, focus, parallax, "
          "incidence) over the vertices of the K worst faces; reconstructability: the share of the "
          "whole mesh's weighted reconstructability deficit the view removes (Smith et al. 2018's "
          "pair heuristic, each face weighted by its PRI rank, unobserved and boundary faces by the "
          "exploration weight; docs/nbv.md)",
          {"paper", "reconstructability"}, [](const O& o) { return energy_kind_name(o.energy_kind); },
          [](O& o, const std::string& w) { o.energy_kind = parse_energy_kind(w); }),
      real_option<O>(
          "gain_target", "Reconstructability target",
          "reconstructability: the reconstructability at which a face needs no more views (a good "
          "pair of views adds up to about 1)",
          left_open(0, 1000), [](const O& o) { return o.gain.target; },
          [](O& o, double x) { o.gain.target = x; }),
      real_option<O>(
          "exploration_weight", "Exploration weight",
          "reconstructability: the weight of an unobserved face or one on the mesh's boundary; "
          "observed faces weigh their PRI rank in (0, 1]",
          closed(0, 100), [](const O& o) { return o.gain.exploration_weight; },
          [](O& o, double x) { o.gain.exploration_weight = x; }),
      int_option<O>(
          "gain_clusters", "Face clusters",
          "reconstructability: faces are scored in about this many compact clusters of one facing "
          "(0 = every face on its own: exact, slower)",
          closed(0, 10000000), [](const O& o) { return std::int64_t(o.gain.clusters); },
          [](O& o, std::int64_t x) { o.gain.clusters = clamp_to_int(x); }),
      [] {
        OptionSpec<O> s{"explore_hull", OptionType::Bool, "Explore the hull",
                        "reconstructability: the part of the mesh's convex hull that no view sees, "
                        "away from the mesh, stands for surface not yet reconstructed and weighs as "
                        "exploration",
                        {}, {}, {}, {}};
        s.get = [](const O& o) { return OptionValue(o.gain.explore_hull); };
        s.set = [](O& o, const OptionValue& v) { o.gain.explore_hull = as_bool("explore_hull", v); };
        return s;
      }(),
      real_option<O>(
          "match_angle", "Match angle",
          "reconstructability: a candidate improves surface that existing views see only where its "
          "ray is within this angle of one of theirs (features match only between nearby "
          "directions); on surface no view sees yet, its gain is scaled by the share of what it "
          "sees that matches. 180 = every pair counts, as in Smith et al.'s heuristic",
          left_open(0, 180, "degrees"), [](const O& o) { return o.gain.match_angle; },
          [](O& o, double x) { o.gain.match_angle = x; }),
      weight("weight_occlusion", "Weight occlusion (m1)", "occlusion", 0),
      weight("weight_focus", "Weight focus (m2)", "focus", 1),
      weight("weight_parallax", "Weight parallax (m3)", "parallax", 2),
      weight("weight_incidence", "Weight incidence (m4)", "incidence", 3),
      real_option<O>(
          "penalty", "Penalty (Kp)",
          "Value of a term when its condition fails (vertex occluded or outside the image, too "
          "small a baseline)",
          closed(-1000, 0), [](const O& o) { return o.energy.penalty; },
          [](O& o, double x) { o.energy.penalty = x; }),
      real_option<O>(
          "parallax_delta", "Parallax threshold",
          "Baseline / depth ratio above which a pair (candidate, existing view) counts as parallax",
          left_open(0, 10), [](const O& o) { return o.energy.parallax_delta; },
          [](O& o, double x) { o.energy.parallax_delta = x; }),
      real_option<O>(
          "incidence_mu", "Incidence mean",
          "Preferred angle (degrees) between the vertex normal and the ray to the camera",
          closed(0, 90, "degrees"), [](const O& o) { return o.energy.incidence_mu; },
          [](O& o, double x) { o.energy.incidence_mu = x; }),
      real_option<O>(
          "incidence_sigma", "Incidence spread",
          "Degrees; the von Mises concentration is 1 / sigma^2 (sigma in radians)",
          closed(0.1, 180, "degrees"), [](const O& o) { return o.energy.incidence_sigma; },
          [](O& o, double x) { o.energy.incidence_sigma = x; }),
      int_option<O>(
          "directions", "Sampled directions", "sampled, refined: directions on the hemisphere",
          closed(1, 65536), [](const O& o) { return o.sampling.directions; },
          [](O& o, std::int64_t x) { o.sampling.directions = clamp_to_int(x); }),
      real_option<O>(
          "safety_distance", "Safety distance",
          "Candidates nearer to the surface than this share of the bounding-box diagonal, or "
          "inside the mesh's volume, are rejected",
          closed(0, 10), [](const O& o) { return o.safety_distance; },
          [](O& o, double x) { o.safety_distance = x; }),
      bool_option<O>("above_ground", "Stay above the ground",
                     "sampled, refined: no pose lower than the mesh's lowest point (its 1st "
                     "percentile of heights along the existing views' level up) plus the safety "
                     "distance, or than the lowest existing view where that is lower: "
                     "photographs are taken above the ground the object stands on (off = the "
                     "paper's whole hemisphere)",
                     &O::above_ground),
      bool_option<O>("level_views", "Level views",
                     "sampled, refined: poses without roll, their image up towards the existing "
                     "views' level up (the direction perpendicular to their right axes), as a "
                     "gimbal takes photos (off = the paper's mean image up of the existing views)",
                     &O::level_views),
      int_option<O>(
          "refine_best", "Refined candidates", "refined: best sampled poses refined per suggestion",
          closed(1, 64), [](const O& o) { return o.refine_best; },
          [](O& o, std::int64_t x) { o.refine_best = clamp_to_int(x); }),
      int_option<O>(
          "refine_iterations", "Refine iterations", "refined: Nelder-Mead iterations per pose",
          closed(0, 10000), [](const O& o) { return o.refine.iterations; },
          [](O& o, std::int64_t x) { o.refine.iterations = clamp_to_int(x); }),
      int_option<O>(
          "seed", "Seed", "Turns the sampling spiral (same seed, same candidates)",
          closed(0, 2147483647), [](const O& o) { return std::int64_t(o.sampling.seed); },
          [](O& o, std::int64_t x) {
            // Negative seeds stay visible to check_options() as out of range.
            o.sampling.seed = x < 0 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(x);
          }),
      int_option<O>(
          "threads", "Threads", kThreadsHelp, threads_range(), [](const O& o) { return o.threads; },
          [](O& o, std::int64_t x) { o.threads = clamp_to_int(x); }),
  };
  return table;
}

std::string cli_flag(const std::string& name) {
  std::string out = "--";
  for (char c : name) out += c == '_' ? '-' : c;
  return out;
}

std::string vtk_name(const std::string& name) {
  std::string out;
  bool upper = true;
  for (char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

namespace {

nlohmann::json to_json(const OptionValue& v) {
  if (const bool* b = std::get_if<bool>(&v)) return *b;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return *i;
  if (const double* d = std::get_if<double>(&v)) return *d;
  return std::get<std::string>(v);
}

OptionValue from_json(const nlohmann::json& j, OptionType type, const std::string& key) {
  switch (type) {
    case OptionType::Bool:
      if (j.is_boolean()) return j.get<bool>();
      break;
    case OptionType::Int:
      if (j.is_number_integer()) return j.get<std::int64_t>();
      if (j.is_number_float()) return j.get<double>();  // integral values accepted by set()
      break;
    case OptionType::Real:
      if (j.is_number()) return j.get<double>();
      break;
    case OptionType::Choice:
      if (j.is_string()) return j.get<std::string>();
      break;
  }
  throw Error("option '" + key + "' takes a " + option_type_name(type) + ", got " + j.dump());
}

template <class Options>
nlohmann::json table_json(const OptionTable<Options>& table) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : table) {
    nlohmann::json e = {{"name", s.name},
                        {"cli", cli_flag(s.name)},
                        {"vtk", vtk_name(s.name)},
                        {"meshlab", s.name},
                        {"label", s.label},
                        {"type", option_type_name(s.type)},
                        {"default", to_json(s.default_value())},
                        {"help", s.help}};
    if (s.type == OptionType::Int || s.type == OptionType::Real) {
      e["range"] = s.range.describe();
      e["min"] = s.range.min;  // +-inf become null
      e["max"] = s.range.max;
      e["min_open"] = s.range.min_open;
      e["max_open"] = s.range.max_open;
      nlohmann::json specials = nlohmann::json::array();
      for (const auto& [value, meaning] : s.range.specials)
        specials.push_back({{"value", value}, {"meaning", meaning}});
      e["specials"] = specials;
      e["unit"] = s.range.unit;
    }
    if (s.type == OptionType::Choice) e["choices"] = s.choices;
    out.push_back(e);
  }
  return out;
}

}  // namespace

template <class Options>
std::string options_json(const Options& options, const OptionTable<Options>& table) {
  // In table order (nlohmann's object would sort the keys).
  std::string out = "{";
  for (const auto& s : table)
    out += (out.size() > 1 ? ", " : "") + nlohmann::json(s.name).dump() + ": " +
           to_json(s.get(options)).dump();
  return out + "}";
}

template <class Options>
void parse_options_json(const std::string& text, const OptionTable<Options>& table,
                        Options* options) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("options are not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw Error("options must be a JSON object {\"name\": value, ...}");
  Options out = *options;
  for (const auto& [key, value] : j.items()) {
    const OptionSpec<Options>* spec = nullptr;
    for (const auto& s : table)
      if (s.name == key) spec = &s;
    if (!spec) throw Error("unknown option '" + key + "'");
    const OptionValue v = from_json(value, spec->type, key);
    spec->set(out, v);
    const std::string problem = spec->problem(spec->get(out));
    if (!problem.empty()) throw Error(problem);
  }
  *options = out;
}

const OptionTable<MissionOptions>& mission_option_table() {
  using O = MissionOptions;
  auto real = [](const char* name, const char* label, const char* help, OptionRange range,
                 double O::*field) {
    return real_option<O>(name, label, help, std::move(range),
                          [field](const O& o) { return o.*field; },
                          [field](O& o, double x) { o.*field = x; });
  };
  const double inf = std::numeric_limits<double>::infinity();
  static const OptionTable<O> table = {
      real("min_altitude", "Min altitude",
           "Metres above the take-off point; no waypoint or leg goes lower (take-off and landing "
           "are vertical)",
           closed(0, 10000, "metres"), &O::min_altitude),
      real("max_altitude", "Max altitude",
           "Metres above the take-off point; no waypoint, leg or detour goes higher",
           left_open(0, 10000, "metres"), &O::max_altitude),
      real("min_mesh_distance", "Min distance to the mesh",
           "Metres; every waypoint and every point of every leg keeps at least this distance "
           "from the mesh",
           left_open(0, 1000, "metres"), &O::min_mesh_distance),
      real("gimbal_pitch_min", "Gimbal pitch min",
           "Degrees (-90 = straight down); no photo looks further down (its pose is moved or dropped)",
           closed(-90, 90, "degrees"), &O::gimbal_pitch_min),
      real("gimbal_pitch_max", "Gimbal pitch max",
           "Degrees (0 = horizontal); no photo looks further up (its pose is moved or dropped)",
           closed(-90, 90, "degrees"), &O::gimbal_pitch_max),
      real("target_gsd", "Target GSD",
           "Centimetres per pixel at the look-at point: caps the camera's distance to focal "
           "length (pixels) x GSD; 0 = no cap",
           with_special(closed(0.01, 1000, "cm/pixel"), 0, "no cap"), &O::target_gsd),
      int_option<O>(
          "max_waypoints", "Max waypoints",
          "Photos per flight at most (a flight with more is split)", closed(1, 10000),
          [](const O& o) { return o.max_waypoints; },
          [](O& o, std::int64_t x) { o.max_waypoints = clamp_to_int(x); }),
      real("speed", "Speed", "Flight speed in m/s (legs, climbs and descents)",
           left_open(0, 50, "m/s"), &O::speed),
      real("time_per_photo", "Time per photo",
           "Seconds spent at each waypoint (stop, turn, gimbal, shot)", closed(0, 600, "seconds"),
           &O::time_per_photo),
      real("battery_minutes", "Battery minutes",
           "Usable minutes per battery: the route is split into flights from and back to the "
           "take-off point that each fit",
           left_open(0, inf, "minutes"), &O::battery_minutes),
      choice_option<O>(
          "infeasible", "Infeasible suggestions",
          "A suggestion that breaks a constraint: move = to the nearest pose that keeps them "
          "all (then re-scored), dropped when there is none; drop = dropped. The output says "
          "which and why",
          {"move", "drop"}, [](const O& o) { return o.infeasible; },
          [](O& o, const std::string& w) { o.infeasible = w; }),
  };
  return table;
}

void MissionOptions::check() const {
  check_options(*this, mission_option_table());
  if (!(min_altitude < max_altitude))
    throw Error("min_altitude must be below max_altitude, got " + format_option_value(min_altitude) +
                " and " + format_option_value(max_altitude));
  if (!(gimbal_pitch_min < gimbal_pitch_max))
    throw Error("gimbal_pitch_min must be below gimbal_pitch_max, got " +
                format_option_value(gimbal_pitch_min) + " and " +
                format_option_value(gimbal_pitch_max));
}

std::string option_tables_json() {
  nlohmann::json j = {{"pri", table_json(pri_option_table())},
                      {"suggest", table_json(suggest_option_table())},
                      {"mission", table_json(mission_option_table())}};
  return j.dump(2) + "\n";
}

// The two tables' instantiations (the only ones).
template struct OptionSpec<PriOptions>;
template struct OptionSpec<SuggestOptions>;
template void check_options(const PriOptions&, const OptionTable<PriOptions>&);
template void check_options(const SuggestOptions&, const OptionTable<SuggestOptions>&);
template std::string options_json(const PriOptions&, const OptionTable<PriOptions>&);
template std::string options_json(const SuggestOptions&, const OptionTable<SuggestOptions>&);
template void parse_options_json(const std::string&, const OptionTable<PriOptions>&, PriOptions*);
template void parse_options_json(const std::string&, const OptionTable<SuggestOptions>&,
                                 SuggestOptions*);
template struct OptionSpec<MissionOptions>;
template void check_options(const MissionOptions&, const OptionTable<MissionOptions>&);
template std::string options_json(const MissionOptions&, const OptionTable<MissionOptions>&);
template void parse_options_json(const std::string&, const OptionTable<MissionOptions>&,
                                 MissionOptions*);

}  // namespace meshnbv
