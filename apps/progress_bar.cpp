#include "progress_bar.h"

#include <cstdio>
#include <unistd.h>

namespace meshnbv::cli {

ProgressBar::ProgressBar(bool quiet, bool json)
    : enabled_(!quiet && (json || ::isatty(STDERR_FILENO))), json_(json && !quiet) {}

ProgressCallback ProgressBar::callback() {
  return [this](double fraction, const std::string& stage) {
    draw(fraction, stage);
    return true;
  };
}

void ProgressBar::draw(double fraction, const std::string& stage) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    if (!stage_.empty() && !json_) std::fputc('\n', stderr);
    stage_ = stage;
    stage_start_ = now;
    last_percent_ = -1;
  }
  const int percent = int(fraction * 100.0);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double eta = fraction > 0.01 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (json_) {
    std::fprintf(stderr, "{\"stage\": \"%s\", \"fraction\": %.3f, \"elapsed\": %.3f, \"eta\": %.3f}\n",
                 stage.c_str(), fraction, elapsed, eta);
    std::fflush(stderr);
    return;
  }
  const int width = 30, filled = int(fraction * width);
  std::fprintf(stderr, "\r%-10s [%.*s%*s] %3d%%  %5.1fs  eta %5.1fs", stage.c_str(), filled,
               "##############################", width - filled, "", percent, elapsed, eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && !json_ && !stage_.empty()) std::fputc('\n', stderr);
  stage_.clear();
}

}  // namespace meshnbv::cli
