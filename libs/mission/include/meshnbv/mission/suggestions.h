// Reading back the suggestions JSON ("meshnbv-suggestions", docs/formats.md)
// that `meshnbv suggest` and `run` write: the suggested cameras, their
// look-at points and energies, the worst regions' faces and the options
// (to re-score a moved suggestion with the same energy).
#pragma once

#include <string>
#include <vector>

#include "meshnbv/mission/plan.h"

namespace meshnbv::mission {

struct SuggestionsFile {
  std::string scene;
  std::vector<MissionInput> suggestions;
  std::vector<std::vector<int>> region_faces;
  std::string options;  // the "options" object as JSON text (suggest table only)
};

// Error (one line, naming the file and the element) for anything that is
// not such a file: wrong format tag, missing fields, bad cameras
// (PinholeCamera::check), region indices out of range.
SuggestionsFile parse_suggestions_json(const std::string& text, const std::string& name);
SuggestionsFile read_suggestions_file(const std::string& path);

}  // namespace meshnbv::mission
