// Our JSON scene format (schema in docs/formats.md):
// { "format": "meshnbv-scene", "version": 1, "mesh": "x.ply" | null,
//   "views": [ { "label": "...", "image": "a.png" | null, "used": true,
//                optional "image_orientation": "stored" | "exif",
//                "camera": { "width", "height", "fx", "fy", "cx", "cy", "k1", "k2",
//                            optional "lens": "brown" | "fisheye", "k3".."k6", "p1", "p2",
//                            "skew", "R": [[3],[3],[3]], "t": [3] } } ] }
// Paths are relative to the JSON file; camera in our convention.
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <utility>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace meshnbv::io {
namespace {

double json_number(const json& j, const char* key, const std::string& file, const std::string& where) {
  if (!j.contains(key)) throw Error(std::string("missing \"") + key + "\"", file, -1, where);
  const json& v = j.at(key);
  if (!v.is_number()) throw Error(std::string("\"") + key + "\" must be a number", file, -1, where);
  return v.get<double>();
}

// An image size: a whole number that fits an int (a cast of 1e300 to int
// would be undefined behaviour).
int json_image_size(const json& j, const char* key, const std::string& file, const std::string& where) {
  const double v = json_number(j, key, file, where);
  if (!(v >= 1 && v <= (1 << 30) && v == std::floor(v)))
    throw Error(
        std::string("\"") + key + "\" must be a whole number of pixels in [1, 2^30], got " + j.at(key).dump(),
        file, -1, where);
  return static_cast<int>(v);
}

// Optional member of a given type: absent or null gives `fallback`; any
// other type is an error naming the key (json::value() would throw a
// nlohmann type_error instead, which is not a meshnbv::Error).
std::string optional_string(const json& j, const char* key, const std::string& fallback,
                            const std::string& file, const std::string& where) {
  if (!j.contains(key) || j.at(key).is_null()) return fallback;
  if (!j.at(key).is_string()) throw Error(std::string("\"") + key + "\" must be a string", file, -1, where);
  return j.at(key).get<std::string>();
}

bool optional_bool(const json& j, const char* key, bool fallback, const std::string& file,
                   const std::string& where) {
  if (!j.contains(key) || j.at(key).is_null()) return fallback;
  if (!j.at(key).is_boolean())
    throw Error(std::string("\"") + key + "\" must be true or false", file, -1, where);
  return j.at(key).get<bool>();
}

// The lens: "lens" ("brown", the default, or "fisheye") and its optional
// parameters (0 when absent).
void read_lens(const json& j, PinholeCamera* c, const std::string& file, const std::string& where) {
  const std::string lens = optional_string(j, "lens", "brown", file, where);
  if (lens == "fisheye")
    c->lens = LensModel::Fisheye;
  else if (lens != "brown")
    throw Error("\"lens\" must be \"brown\" or \"fisheye\", got \"" + lens + "\"", file, -1, where);
  const std::pair<const char*, double PinholeCamera::*> params[] = {
      {"k1", &PinholeCamera::k1}, {"k2", &PinholeCamera::k2}, {"k3", &PinholeCamera::k3},
      {"k4", &PinholeCamera::k4}, {"k5", &PinholeCamera::k5}, {"k6", &PinholeCamera::k6},
      {"p1", &PinholeCamera::p1}, {"p2", &PinholeCamera::p2}, {"skew", &PinholeCamera::skew}};
  for (const auto& [key, member] : params)
    if (j.contains(key)) c->*member = json_number(j, key, file, where);
}

// k1, k2 always; the rest of the lens only when set, so that pinhole and
// radial scenes read the same as before the lens models.
void write_lens(const PinholeCamera& c, json* cam) {
  (*cam)["k1"] = c.k1;
  (*cam)["k2"] = c.k2;
  if (c.lens == LensModel::Fisheye) (*cam)["lens"] = "fisheye";
  const std::pair<const char*, double> params[] = {{"k3", c.k3}, {"k4", c.k4}, {"k5", c.k5},    {"k6", c.k6},
                                                   {"p1", c.p1}, {"p2", c.p2}, {"skew", c.skew}};
  for (const auto& [key, value] : params)
    if (value != 0.0) (*cam)[key] = value;
}

PinholeCamera camera_from_json(const json& j, const std::string& file, const std::string& where) {
  if (!j.is_object()) throw Error("\"camera\" must be an object", file, -1, where);
  PinholeCamera c;
  c.width = json_image_size(j, "width", file, where);
  c.height = json_image_size(j, "height", file, where);
  c.fx = json_number(j, "fx", file, where);
  c.fy = json_number(j, "fy", file, where);
  c.cx = json_number(j, "cx", file, where);
  c.cy = json_number(j, "cy", file, where);
  read_lens(j, &c, file, where);
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
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for numbers beyond double ("1e400")
    throw Error(std::string("malformed JSON: ") + e.what(), path);
  }
  const std::string not_ours = "not a MeshNBV scene (expected \"format\": \"meshnbv-scene\")";
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != "meshnbv-scene")
    throw Error(not_ours, path);
  if (!doc.contains("version") || doc["version"] != 1)
    throw Error("\"version\" must be 1, got " +
                    (doc.contains("version") ? doc["version"].dump() : std::string("none")),
                path);
  const std::string base = fs::path(path).parent_path().string();
  Scene scene;
  scene.source = path;
  scene.format = "json";
  const std::string mesh = optional_string(doc, "mesh", "", path, "");
  if (!mesh.empty()) {
    scene.mesh_path = resolve(mesh, base);
    scene.mesh = read_mesh(scene.mesh_path);
  }
  const json& views = doc.contains("views") ? doc["views"] : json::array();
  if (!views.is_array()) throw Error("\"views\" must be an array", path);
  for (std::size_t i = 0; i < views.size(); ++i) {
    const json& jv = views[i];
    const std::string where = "view " + std::to_string(i);
    if (!jv.is_object()) throw Error("must be an object", path, -1, where);
    View v;
    v.label = optional_string(jv, "label", "view_" + std::to_string(i), path, where);
    const std::string image = optional_string(jv, "image", "", path, where);
    if (!image.empty()) v.image_path = resolve(image, base);
    v.used = optional_bool(jv, "used", true, path, where);
    const std::string orientation = optional_string(jv, "image_orientation", "stored", path, where);
    if (orientation == "exif")
      v.orientation = ImageOrientation::exif;
    else if (orientation != "stored")
      throw Error("\"image_orientation\" must be \"stored\" or \"exif\", not \"" + orientation + "\"", path,
                  -1, where);
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
    json cam = {{"width", c.width}, {"height", c.height}, {"fx", c.fx},
                {"fy", c.fy},       {"cx", c.cx},         {"cy", c.cy}};
    write_lens(c, &cam);
    cam["R"] = {{c.R(0, 0), c.R(0, 1), c.R(0, 2)},
                {c.R(1, 0), c.R(1, 1), c.R(1, 2)},
                {c.R(2, 0), c.R(2, 1), c.R(2, 2)}};
    cam["t"] = {c.t.x(), c.t.y(), c.t.z()};
    json jv = {
        {"label", v.label},
        {"image", v.has_image() ? json(relative_to(v.image_file("a JSON scene"), base)) : json(nullptr)},
        {"used", v.used},
        {"camera", cam}};
    if (v.orientation == ImageOrientation::exif) jv["image_orientation"] = "exif";
    views.push_back(std::move(jv));
  }
  doc["views"] = views;
  // JSON text is UTF-8: a label or path that is not (e.g. Latin-1 read from
  // a .mlp) makes dump() throw; name the view instead, before writing.
  std::string text;
  try {
    text = doc.dump(2);
  } catch (const json::exception&) {
    std::string what = "the mesh path";
    for (std::size_t i = 0; i < views.size(); ++i) {
      try {
        (void)views[i].dump();
      } catch (const json::exception&) {
        what = "view " + std::to_string(i) + ": the label or image path";
        break;
      }
    }
    throw Error(what + " is not valid UTF-8, which JSON cannot hold; write .mlp or COLMAP instead", path);
  }
  write_atomically(
      path, [&](std::ostream& out) { out << text << "\n"; }, overwrite);
}

}  // namespace meshnbv::io
