#include "meshnbv/error.h"

#include <charconv>
#include <cmath>

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

std::string format_option_value(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[64];
  if (value == std::floor(value) && std::abs(value) < 1e15) {  // whole numbers as integers
    const auto r = std::to_chars(buf, buf + sizeof(buf), static_cast<long long>(value));
    return std::string(buf, r.ptr);
  }
  const auto r = std::to_chars(buf, buf + sizeof(buf), value);
  return std::string(buf, r.ptr);
}

void check_option(bool ok, const std::string& name, const std::string& range, double value) {
  if (!ok) throw Error(name + " must be " + range + ", got " + format_option_value(value));
}

void report_progress(const ProgressCallback& callback, double fraction, const std::string& stage) {
  if (callback && !callback(fraction, stage)) throw Cancelled();
}

}  // namespace meshnbv
