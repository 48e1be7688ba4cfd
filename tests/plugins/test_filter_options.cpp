// The plugin's parameters against the core's option tables (#20): the
// names, types and defaults are compared by options/front_ends; here, in
// process, every numeric parameter set just outside its range makes the
// filter fail with the table's message (name and range), and one at each
// end of the range does not fail because of it.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "filter_meshnbv.h"
#include "meshnbv/options.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace {

using meshnbv::OptionRange;
using meshnbv::OptionType;

// Values just outside the range (never one of its special values).
std::vector<double> outside(const OptionRange& r, OptionType type) {
  const double step = type == OptionType::Int ? 1.0 : 1e-3;
  std::vector<double> out;
  auto special = [&](double x) {
    for (const auto& s : r.specials)
      if (s.first == x) return true;
    return false;
  };
  if (std::isfinite(r.min)) {
    double x = r.min_open ? r.min : r.min - step;
    while (special(x)) x -= step;
    out.push_back(x);
  }
  if (std::isfinite(r.max)) out.push_back(r.max_open ? r.max : r.max + step);
  return out;
}

// The filter's parameters at their defaults with `name` set to `value`.
RichParameterList with_value(FilterMeshNbvPlugin& plugin, int id, const std::string& name,
                             OptionType type, double value) {
  MeshDocument scratch;
  RichParameterList par;
  plugin.initParameterSet(plugin.AC(id), scratch, par);
  const QString key = QString::fromStdString(name);
  if (type == OptionType::Int)
    par.setValue(key, IntValue(int(value)));
  else
    par.setValue(key, FloatValue(float(value)));
  return par;
}

// Runs the filter on a document holding one empty mesh layer (with face
// quality, so that Select Worst Faces gets to its parameters) and returns
// its error message ("" when it succeeded).
std::string error_of(FilterMeshNbvPlugin& plugin, int id, const RichParameterList& par) {
  MeshDocument document;
  MeshModel* model = document.addNewMesh("", "mesh", true);
  model->updateDataMask(MeshModel::MM_FACEQUALITY);
  if (plugin.applyFilter(plugin.AC(id), document, par, nullptr)) return "";
  return plugin.errorMsg().toStdString();
}

template <class Options>
void check_ranges(int id, const meshnbv::OptionTable<Options>& table,
                  const std::vector<std::string>& only = {}) {
  FilterMeshNbvPlugin plugin;
  int checked = 0;
  for (const auto& spec : table) {
    if (!only.empty() && std::find(only.begin(), only.end(), spec.name) == only.end()) continue;
    if (spec.type != OptionType::Int && spec.type != OptionType::Real) continue;
    SCOPED_TRACE(spec.name);
    const std::string expected = spec.name + " must be " + spec.range.describe();
    for (double x : outside(spec.range, spec.type)) {
      if (spec.type == OptionType::Int && std::fabs(x) > std::numeric_limits<int>::max()) continue;
      const std::string error = error_of(plugin, id, with_value(plugin, id, spec.name, spec.type, x));
      EXPECT_NE(error.find(expected), std::string::npos) << "value " << x << ": " << error;
      ++checked;
    }
    // The ends themselves pass the parameter check (the filter then fails
    // for want of rasters, not because of the value).
    for (double x : {spec.range.min, spec.range.max}) {
      if (!std::isfinite(x) || (x == spec.range.min && spec.range.min_open) ||
          (x == spec.range.max && spec.range.max_open))
        continue;
      if (spec.type == OptionType::Int && std::fabs(x) > std::numeric_limits<int>::max()) continue;
      if (spec.type == OptionType::Real && double(float(x)) != x && !spec.range.contains(float(x)))
        continue;  // MeshLab's float cannot hold this end exactly
      const std::string error = error_of(plugin, id, with_value(plugin, id, spec.name, spec.type, x));
      EXPECT_EQ(error.find(spec.name + " must be"), std::string::npos) << "value " << x << ": " << error;
    }
  }
  EXPECT_GT(checked, 0);
}

}  // namespace

TEST(FilterOptions, ComputePriRefusesEveryParameterOutsideItsRange) {
  check_ranges(FilterMeshNbvPlugin::FP_COMPUTE_PRI, meshnbv::pri_option_table());
}

TEST(FilterOptions, SuggestNextViewRefusesEveryParameterOutsideItsRange) {
  check_ranges(FilterMeshNbvPlugin::FP_SUGGEST_NEXT_VIEW, meshnbv::suggest_option_table());
}

TEST(FilterOptions, SelectWorstFacesRefusesWorstFacesOutsideItsRange) {
  check_ranges(FilterMeshNbvPlugin::FP_SELECT_WORST_FACES, meshnbv::suggest_option_table(),
               {"worst_faces"});
}
