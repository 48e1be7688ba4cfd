#include "meshnbv/error.h"

#include "meshnbv/progress.h"

namespace meshnbv {
namespace {
std::string compose(const std::string& message, const std::string& file, long line,
                    const std::string& element) {
  std::string out;
  if (!file.empty()) {
    out += file;
    if (line > 0) out += ":" + std::to_string(line);
    out += ": ";
  }
  if (!element.empty()) out += element + ": ";
  return out + message;
}
}  // namespace

Error::Error(const std::string& message) : std::runtime_error(message), reason_(message) {}

Error::Error(const std::string& message, const std::string& file, long line,
             const std::string& element)
    : std::runtime_error(compose(message, file, line, element)),
      reason_(message),
      file_(file),
      line_(line),
      element_(element) {}

void report_progress(const ProgressCallback& callback, double fraction, const std::string& stage) {
  if (callback && !callback(fraction, stage)) throw Cancelled();
}

}  // namespace meshnbv
