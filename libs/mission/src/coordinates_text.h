// Comma-separated numbers of a flag's text ("x,y,z"), private to
// meshnbv::mission: each parsed by io::parse_double (an Error naming the
// flag for a word that is not a number); the caller checks the count.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "meshnbv/io/file_util.h"

namespace meshnbv::mission {

inline std::vector<double> comma_numbers(const std::string& text, const std::string& flag) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) v.push_back(io::parse_double(item, flag, -1, "coordinate"));
  return v;
}

}  // namespace meshnbv::mission
