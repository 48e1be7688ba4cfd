#include "sfm_json.h"

#include <cmath>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"

namespace meshnbv::io::sfm_json {

json parse(const std::string& path) {
  const std::string text = read_file(path);
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw Error(std::string("malformed JSON: ") + e.what(), path);
  }
}

const json& member(const json& j, const char* key, const std::string& file, const std::string& where) {
  if (!j.is_object() || !j.contains(key))
    throw Error(std::string("missing \"") + key + "\"", file, -1, where);
  return j.at(key);
}

double number(const json& j, const std::string& file, const std::string& where) {
  double v = NAN;
  if (j.is_number()) {
    v = j.get<double>();
  } else if (j.is_string()) {
    v = parse_double(j.get<std::string>(), file, -1, where);
  } else {
    throw Error("expected a number, got " + j.dump().substr(0, 40), file, -1, where);
  }
  if (!std::isfinite(v)) throw Error("expected a finite number", file, -1, where);
  return v;
}

long long integer(const json& j, const std::string& file, const std::string& where) {
  const double v = number(j, file, where);
  if (!(std::abs(v) < 9.0e15) || v != std::floor(v))
    throw Error("expected a whole number, got " + j.dump().substr(0, 40), file, -1, where);
  return static_cast<long long>(v);
}

std::vector<double> numbers(const json& j, std::size_t n, const std::string& file,
                            const std::string& where) {
  if (!j.is_array() || (n && j.size() != n))
    throw Error("expected an array of " + (n ? std::to_string(n) : std::string("some")) + " numbers",
                file, -1, where);
  std::vector<double> out;
  for (const json& v : j) out.push_back(number(v, file, where));
  return out;
}

int image_size(const json& j, const std::string& file, const std::string& where) {
  const long long v = integer(j, file, where);
  if (v <= 0 || v > (1 << 30)) throw Error("image size must be in [1, 2^30]", file, -1, where);
  return int(v);
}

std::string text(const json& j, const std::string& file, const std::string& where) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_number_integer() || j.is_number_unsigned()) return j.dump();
  throw Error("expected a string or an integer", file, -1, where);
}

void set_brown(const std::vector<double>& d, PinholeCamera* c) {
  c->k1 = d[0], c->k2 = d[1], c->k3 = d[2];
  c->p1 = d[3], c->p2 = d[4];
}

}  // namespace meshnbv::io::sfm_json
