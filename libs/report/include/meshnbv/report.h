// The visual report of a run: report.html (self-contained: pictures
// embedded) plus the PNGs it shows.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv {

struct ReportInputs {
  const Scene* scene = nullptr;
  const PriResult* pri = nullptr;
  PriOptions pri_options;
  const SuggestResult* suggestions = nullptr;
  SuggestOptions suggest_options;
  std::string scene_path;
  std::vector<std::pair<std::string, double>> timings;      // step, seconds
  std::vector<std::pair<std::string, std::string>> files;   // file name, what it is
  int image_width = 960, image_height = 720;                // overview pictures
  int suggestion_views = 3;                                 // pictures from the top suggestions
};

struct ReportFiles {
  std::string html;
  std::vector<std::string> pictures;
};

// Renders the pictures with our renderer and writes them and report.html
// into `folder`. Progress stage "report".
ReportFiles write_report(const ReportInputs& inputs, const std::string& folder,
                         const ProgressCallback& progress = {});

}  // namespace meshnbv
