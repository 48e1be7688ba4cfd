// Progress of long steps: a bar with ETA on a terminal (stderr), nothing
// when stderr is not a terminal or with --quiet, and one JSON object per
// line on stderr with --json ({"stage", "fraction", "elapsed", "eta"}) for
// tools that wrap the CLI.
#pragma once

#include <chrono>
#include <string>

#include "meshnbv/progress.h"

namespace meshnbv::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet, bool json = false);
  ProgressCallback callback();
  void finish();

 private:
  void draw(double fraction, const std::string& stage);
  bool enabled_;
  bool json_;
  std::string stage_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point stage_start_;
};

}  // namespace meshnbv::cli
