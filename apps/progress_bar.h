// Terminal progress for long steps: a bar on a terminal, silent otherwise
// or with --quiet.
#pragma once

#include <chrono>
#include <string>

#include "meshnbv/progress.h"

namespace meshnbv::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ProgressCallback callback();
  void finish();

 private:
  void draw(double fraction, const std::string& stage);
  bool enabled_;
  std::string stage_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point stage_start_;
};

}  // namespace meshnbv::cli
