// The one error type of the MeshNBV core. Every reader, checker and algorithm
// throws meshnbv::Error with a message a user can act on; front ends translate
// it at their edge (CLI: one line on stderr and a non-zero exit; VTK:
// vtkErrorMacro; MeshLab: Log + failed filter).
#pragma once

#include <stdexcept>
#include <string>

namespace meshnbv {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
  // `file` is the input being read, `line` a 1-based line number (or -1),
  // `element` names the element at fault (e.g. "face 12", "raster 'a.png'").
  Error(const std::string& message, const std::string& file, long line = -1,
        const std::string& element = {});

  const std::string& file() const noexcept { return file_; }
  long line() const noexcept { return line_; }
  const std::string& element() const noexcept { return element_; }
  // The message without the file/line prefix.
  const std::string& reason() const noexcept { return reason_; }

 private:
  std::string reason_;
  std::string file_;
  long line_ = -1;
  std::string element_;
};

// Option checks (the check() of every options struct): throws
// Error("<name> must be <range>, got <value>") unless `ok`, e.g.
// "samples_per_side must be 0 (automatic) or in [2, 64], got 1000".
// `value` is printed in the shortest form that reads back (nan, inf, 1e+308).
void check_option(bool ok, const std::string& name, const std::string& range, double value);
std::string format_option_value(double value);

// Thrown when a progress callback asked to stop.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled by the user") {}
};

}  // namespace meshnbv
