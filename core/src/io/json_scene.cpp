// Our JSON scene format (schema in docs/formats.md):
// { "format": "meshnbv-scene", "version": 1, "mesh": "x.ply" | null,
//   "views": [ { "label": "...", "image": "a.png" | null, "used": true,
//                "camera": { "width", "height", "fx", "fy", "cx", "cy", "k1", "k2",
//                            "R": [[3],[3],[3]], "t": [3] } } ] }
// Paths are relative to the JSON file; camera in our convention.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace meshnbv::io {
namespace {

double number(const json& j, const char* key, const std::string& file, const std::string& where) {
  if (!j.contains(key)) throw Error(std::string("missing \"") + key + "\"", file, -1, where);
  const json& v = j.at(key);
  if (!v.is_number()) throw Error(std::string("\"") + key + "\" must be a number", file, -1, where);
  return v.get<double>();
}

PinholeCamera camera_from_json(const json& j, const std::string& file, const std::string& where) {
  if (!j.is_object()) throw Error("\"camera\" must be an object", file, -1, where);
  PinholeCamera c;
  c.width = static_cast<int>(number(j, "width", file, where));
  c.height = static_cast<int>(number(j, "height", file, where));
  c.fx = number(j, "fx", file, where);
  c.fy = number(j, "fy", file, where);
  c.cx = number(j, "cx", file, where);
  c.cy = number(j, "cy", file, where);
  c.k1 = j.contains("k1") ? number(j, "k1", file, where) : 0.0;
  c.k2 = j.contains("k2") ? number(j, "k2", file, where) : 0.0;
  const json& R = j.value("R", json());
  const json& t = j.value("t", json());
  if (!R.is_array() || R.size() != 3) throw Error("\"R\" must be 3 rows of 3 numbers", file, -1, where);
  for (int r = 0; r < 3; ++r) {
    if (!R[r].is_array() || R[r].size() != 3)
      throw Error("\"R\" must be 3 rows of 3 numbers", file, -1, where);
    for (int k = 0; k < 3; ++k) {
      if (!R[r][k].is_number()) throw Error("\"R\" entries must be numbers", file, -1, where);
      c.R(r, k) = R[r][k].get<double>();
    }
  }
  if (!t.is_array() || t.size() != 3) throw Error("\"t\" must be 3 numbers", file, -1, where);
  for (int k = 0; k < 3; ++k) {
    if (!t[k].is_number()) throw Error("\"t\" entries must be numbers", file, -1, where);
    c.t(k) = t[k].get<double>();
  }
  c.check(file + ": " + where);
  return c;
}

}  // namespace

Scene read_json_scene(const std::string& path) {
  const std::string text = read_file(path);
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(std::string("malformed JSON: ") + e.what(), path);
  }
  if (!doc.is_object() || doc.value("format", "") != "meshnbv-scene")
    throw Error("not a MeshNBV scene (expected \"format\": \"meshnbv-scene\")", path);
  if (doc.value("version", 0) != 1)
    throw Error("unsupported scene version " + doc.value("version", json(0)).dump(), path);
  const std::string base = fs::path(path).parent_path().string();
  Scene scene;
  scene.source = path;
  scene.format = "json";
  if (doc.contains("mesh") && doc["mesh"].is_string()) {
    scene.mesh_path = resolve(doc["mesh"].get<std::string>(), base);
    scene.mesh = read_mesh(scene.mesh_path);
  }
  const json& views = doc.value("views", json::array());
  if (!views.is_array()) throw Error("\"views\" must be an array", path);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const json& jv = views[i];
    const std::string where = "view " + std::to_string(i);
    if (!jv.is_object()) throw Error("must be an object", path, -1, where);
    View v;
    v.label = jv.value("label", "view_" + std::to_string(i));
    if (jv.contains("image") && jv["image"].is_string())
      v.image_path = resolve(jv["image"].get<std::string>(), base);
    v.used = jv.value("used", true);
    if (!jv.contains("camera")) throw Error("missing \"camera\"", path, -1, where);
    v.camera = camera_from_json(jv["camera"], path, where + " ('" + v.label + "')");
    scene.views.push_back(std::move(v));
  }
  return scene;
}

void write_json_scene(const Scene& scene, const std::string& path, const std::string& mesh_file,
                      bool overwrite) {
  const std::string base = fs::path(path).parent_path().string();
  json doc;
  doc["format"] = "meshnbv-scene";
  doc["version"] = 1;
  doc["mesh"] = mesh_file.empty() ? json(nullptr) : json(relative_to(mesh_file, base));
  json views = json::array();
  for (const auto& v : scene.views) {
    const PinholeCamera& c = v.camera;
    json cam = {{"width", c.width}, {"height", c.height}, {"fx", c.fx}, {"fy", c.fy},
                {"cx", c.cx},       {"cy", c.cy},         {"k1", c.k1}, {"k2", c.k2}};
    cam["R"] = {{c.R(0, 0), c.R(0, 1), c.R(0, 2)},
                {c.R(1, 0), c.R(1, 1), c.R(1, 2)},
                {c.R(2, 0), c.R(2, 1), c.R(2, 2)}};
    cam["t"] = {c.t.x(), c.t.y(), c.t.z()};
    views.push_back({{"label", v.label},
                     {"image", v.has_image() ? json(relative_to(v.image_path, base)) : json(nullptr)},
                     {"used", v.used},
                     {"camera", cam}});
  }
  doc["views"] = views;
  write_atomically(path, [&](std::ostream& out) { out << doc.dump(2) << "\n"; }, overwrite);
}

}  // namespace meshnbv::io
