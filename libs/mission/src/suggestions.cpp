// The suggestions JSON read back (suggestions.h).
#include "meshnbv/mission/suggestions.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"

namespace meshnbv::mission {
namespace {

using nlohmann::json;

double num(const json& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number())
    throw Error(where + ": \"" + key + "\" must be a number");
  const double v = j[key].get<double>();
  if (!std::isfinite(v)) throw Error(where + ": \"" + key + "\" must be finite");
  return v;
}

Vec3 vec3(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw Error(where + " must be 3 numbers");
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!j[std::size_t(k)].is_number()) throw Error(where + " must be 3 numbers");
    v[k] = j[std::size_t(k)].get<double>();
  }
  if (!v.allFinite()) throw Error(where + " must be finite");
  return v;
}

PinholeCamera camera(const json& j, const std::string& where) {
  if (!j.is_object()) throw Error(where + ": \"camera\" must be an object");
  PinholeCamera c;
  const double w = num(j, "width", where), h = num(j, "height", where);
  if (!(w >= 1 && w <= 1e6 && h >= 1 && h <= 1e6)) throw Error(where + ": bad image size");
  c.width = int(w);
  c.height = int(h);
  c.fx = num(j, "fx", where);
  c.fy = num(j, "fy", where);
  c.cx = num(j, "cx", where);
  c.cy = num(j, "cy", where);
  const json& r = j.contains("R") ? j["R"] : json();
  if (!r.is_array() || r.size() != 3) throw Error(where + ": \"R\" must be 3 rows");
  for (int i = 0; i < 3; ++i) c.R.row(i) = vec3(r[std::size_t(i)], where + " R row").transpose();
  c.t = vec3(j.contains("t") ? j["t"] : json(), where + " t");
  c.check(where);
  return c;
}

}  // namespace

SuggestionsFile parse_suggestions_json(const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception&) {
    throw Error("not valid JSON", name);
  }
  SuggestionsFile out;
  try {
    if (!j.is_object() || j.value("format", "") != "meshnbv-suggestions")
      throw Error("not a suggestions file (format \"meshnbv-suggestions\" from meshnbv suggest)");
    out.scene = j.value("scene", "");
    if (j.contains("regions") && j["regions"].is_array())
      for (const json& r : j["regions"]) {
        std::vector<int> faces;
        if (r.is_object() && r.contains("faces") && r["faces"].is_array())
          for (const json& f : r["faces"])
            if (f.is_number_integer() && f.get<long long>() >= 0 && f.get<long long>() < (1LL << 31))
              faces.push_back(int(f.get<long long>()));
        out.region_faces.push_back(faces);
      }
    if (!j.contains("suggestions") || !j["suggestions"].is_array() || j["suggestions"].empty())
      throw Error("the file holds no suggestions");
    for (std::size_t i = 0; i < j["suggestions"].size(); ++i) {
      const json& s = j["suggestions"][i];
      const std::string where = "suggestion " + std::to_string(i + 1);
      if (!s.is_object()) throw Error(where + " must be an object");
      MissionInput m;
      m.label = s.contains("label") && s["label"].is_string() ? s["label"].get<std::string>() : where;
      m.rank = s.contains("rank") && s["rank"].is_number_integer() ? s["rank"].get<int>() : int(i + 1);
      m.region = s.contains("region") && s["region"].is_number_integer() ? s["region"].get<int>() : 0;
      if (m.region < 0 || (!out.region_faces.empty() && std::size_t(m.region) >= out.region_faces.size()))
        throw Error(where + ": region " + std::to_string(m.region) + " does not exist");
      m.camera = camera(s.contains("camera") ? s["camera"] : json(), where);
      m.look_at = vec3(s.contains("look_at") ? s["look_at"] : json(), where + " look_at");
      if (s.contains("energy") && s["energy"].is_object() && s["energy"].contains("total") &&
          s["energy"]["total"].is_number())
        m.energy = s["energy"]["total"].get<double>();
      out.suggestions.push_back(m);
    }
    if (j.contains("options") && j["options"].is_object()) {
      json o = j["options"];
      o.erase("distance_factors");
      out.options = o.dump();
    }
  } catch (const json::exception& e) {
    throw Error(std::string("malformed suggestions: ") + e.what(), name);
  } catch (const Error& e) {
    if (!e.file().empty()) throw;
    throw Error(e.reason(), name);
  }
  return out;
}

SuggestionsFile read_suggestions_file(const std::string& path) {
  return parse_suggestions_json(io::read_file(path), path);
}

}  // namespace meshnbv::mission
