// OpenMVG sfm_data.json (cereal JSON; sfm_data_version 0.2, 0.3), the
// output of openMVG_main_SfM / openMVG_main_ConvertSfM_DataFormat:
//   "root_path": image folder
//   "views": [{ "key", "value": { "ptr_wrapper": { "data": { "local_path", "filename",
//              "width", "height", "id_view", "id_intrinsic", "id_pose" }}}}]
//   "intrinsics": [{ "key", "value": { "polymorphic_id", "polymorphic_name" (first of
//              its type only), "ptr_wrapper": { "data": { "width", "height",
//              "focal_length", "principal_point": [2], lens }}}}]
//   "extrinsics": [{ "key", "value": { "rotation": [[3],[3],[3]], "center": [3] }}]
//   "structure": [{ "key", "value": { "X": [3], "observations": [{ "key": id_view,
//              "value": { "id_feat", "x": [2] }}]}}]
// Conventions (openMVG/cameras, geometry/pose3.hpp): x_cam = R (X - C), camera
// along +z, y down: ours with t = -R C. Pixel = focal * distorted + principal
// point; OpenMVG states no pixel-centre convention: integer coordinates are
// taken as pixel centres (as Middlebury), so nothing is shifted.
// Lenses: "pinhole"; "pinhole_radial_k1" (disto_k1: k1); "pinhole_radial_k3"
// (disto_k3: k1 k2 k3); "pinhole_brown_t2" (disto_t2: k1 k2 k3 t1 t2, t1 and
// t2 being OpenCV's p1, p2); "fisheye" (fisheye: k1..k4, OpenCV's fisheye).
// Other intrinsic types are an Error naming the type.
#include <filesystem>
#include <map>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"
#include "sfm_json.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

using namespace sfm_json;

PinholeCamera intrinsic_camera(const std::string& type, const json& d, const std::string& file,
                               const std::string& where) {
  PinholeCamera c;
  c.width = image_size(member(d, "width", file, where), file, where + " width");
  c.height = image_size(member(d, "height", file, where), file, where + " height");
  c.fx = c.fy = number(member(d, "focal_length", file, where), file, where + " focal_length");
  const auto pp = numbers(member(d, "principal_point", file, where), 2, file, where + " principal_point");
  c.cx = pp[0];
  c.cy = pp[1];
  if (type == "pinhole_radial_k1") {
    c.k1 = numbers(member(d, "disto_k1", file, where), 1, file, where + " disto_k1")[0];
  } else if (type == "pinhole_radial_k3") {
    const auto k = numbers(member(d, "disto_k3", file, where), 3, file, where + " disto_k3");
    c.k1 = k[0], c.k2 = k[1], c.k3 = k[2];
  } else if (type == "pinhole_brown_t2") {
    set_brown(numbers(member(d, "disto_t2", file, where), 5, file, where + " disto_t2"), &c);
  } else if (type == "fisheye") {
    const auto k = numbers(member(d, "fisheye", file, where), 4, file, where + " fisheye");
    c.lens = LensModel::Fisheye;
    c.k1 = k[0], c.k2 = k[1], c.k3 = k[2], c.k4 = k[3];
  } else if (type != "pinhole") {
    throw Error("intrinsic type '" + type +
                    "' is not supported (pinhole, pinhole_radial_k1, pinhole_radial_k3, "
                    "pinhole_brown_t2, fisheye)",
                file, -1, where);
  }
  c.check(file + ": " + where);
  return c;
}

// cereal writes a polymorphic type's name only at its first occurrence,
// with the high bit of polymorphic_id set; later ones carry the id alone.
std::map<long long, PinholeCamera> read_intrinsics(const json& doc, const std::string& file) {
  std::map<long long, std::string> names;
  std::map<long long, PinholeCamera> out;
  const json& list = member(doc, "intrinsics", file, "");
  if (!list.is_array()) throw Error("\"intrinsics\" must be an array", file);
  for (const json& entry : list) {
    const long long key = integer(member(entry, "key", file, "intrinsic"), file, "intrinsic key");
    const std::string where = "intrinsic " + std::to_string(key);
    const json& value = member(entry, "value", file, where);
    const long long id = integer(member(value, "polymorphic_id", file, where), file, where) & 0x7fffffffLL;
    if (value.contains("polymorphic_name"))
      names[id] = text(value.at("polymorphic_name"), file, where + " polymorphic_name");
    if (!names.count(id))
      throw Error("polymorphic_id " + std::to_string(id) + " names no type seen before", file, -1, where);
    const json& data = member(member(value, "ptr_wrapper", file, where), "data", file, where);
    out[key] = intrinsic_camera(names[id], data, file, where + " ('" + names[id] + "')");
  }
  return out;
}

std::map<long long, std::pair<Mat3, Vec3>> read_extrinsics(const json& doc, const std::string& file) {
  std::map<long long, std::pair<Mat3, Vec3>> out;
  const json& list = doc.contains("extrinsics") ? doc.at("extrinsics") : json::array();
  if (!list.is_array()) throw Error("\"extrinsics\" must be an array", file);
  for (const json& entry : list) {
    const long long key = integer(member(entry, "key", file, "extrinsic"), file, "extrinsic key");
    const std::string where = "extrinsic " + std::to_string(key);
    const json& value = member(entry, "value", file, where);
    const json& rows = member(value, "rotation", file, where);
    if (!rows.is_array() || rows.size() != 3) throw Error("\"rotation\" must be 3 rows", file, -1, where);
    Mat3 R;
    for (int r = 0; r < 3; ++r) {
      const auto row = numbers(rows[std::size_t(r)], 3, file, where + " rotation");
      for (int c = 0; c < 3; ++c) R(r, c) = row[std::size_t(c)];
    }
    const auto C = numbers(member(value, "center", file, where), 3, file, where + " center");
    out[key] = {R, Vec3(C[0], C[1], C[2])};
  }
  return out;
}

void read_structure(const json& doc, const std::map<long long, int>& view_index,
                    const std::string& file, Scene* scene) {
  if (!doc.contains("structure")) return;
  const json& list = doc.at("structure");
  if (!list.is_array()) throw Error("\"structure\" must be an array", file);
  for (const json& entry : list) {
    const json& value = member(entry, "value", file, "structure");
    SparsePoint p;
    const auto X = numbers(member(value, "X", file, "structure"), 3, file, "structure X");
    p.position = Vec3(X[0], X[1], X[2]);
    const json& obs = member(value, "observations", file, "structure");
    if (!obs.is_array()) throw Error("\"observations\" must be an array", file);
    for (const json& o : obs) {
      const long long view = integer(member(o, "key", file, "observation"), file, "observation key");
      const auto x = numbers(member(member(o, "value", file, "observation"), "x", file, "observation"), 2,
                             file, "observation x");
      const auto it = view_index.find(view);
      if (it != view_index.end()) p.observations.emplace_back(it->second, Vec2(x[0], x[1]));
    }
    scene->sparse_points.push_back(std::move(p));
  }
}

}  // namespace

Scene read_openmvg(const std::string& path, const std::string& image_dir) {
  const json doc = parse(path);
  if (!doc.is_object() || !doc.contains("sfm_data_version"))
    throw Error("not an OpenMVG sfm_data.json (no \"sfm_data_version\")", path);
  Scene scene;
  scene.format = "openmvg";
  scene.source = path;
  scene.producer = "OpenMVG (sfm_data.json, version " +
                   text(doc.at("sfm_data_version"), path, "sfm_data_version") + ")";
  const auto intrinsics = read_intrinsics(doc, path);
  const auto extrinsics = read_extrinsics(doc, path);
  const std::string root = doc.contains("root_path") ? text(doc.at("root_path"), path, "root_path") : "";
  const ImageIndex index = image_dir.empty() ? ImageIndex() : ImageIndex(image_dir);
  const json& views = member(doc, "views", path, "");
  if (!views.is_array()) throw Error("\"views\" must be an array", path);
  std::map<long long, int> view_index;
  std::size_t unposed = 0, missing = 0;
  for (const json& entry : views) {
    const long long key = integer(member(entry, "key", path, "view"), path, "view key");
    const std::string where = "view " + std::to_string(key);
    const json& d = member(member(member(entry, "value", path, where), "ptr_wrapper", path, where),
                           "data", path, where);
    const auto intr = intrinsics.find(integer(member(d, "id_intrinsic", path, where), path, where));
    const auto pose = extrinsics.find(integer(member(d, "id_pose", path, where), path, where));
    if (intr == intrinsics.end() || pose == extrinsics.end()) {
      ++unposed;
      continue;
    }
    View v;
    v.label = text(member(d, "filename", path, where), path, where + " filename");
    v.camera = intr->second;
    if (image_size(member(d, "width", path, where), path, where) != v.camera.width ||
        image_size(member(d, "height", path, where), path, where) != v.camera.height)
      throw Error("the view's image size differs from its intrinsic's", path, -1, where + " ('" + v.label + "')");
    v.camera.R = pose->second.first;
    v.camera.set_center(pose->second.second);
    v.camera.check(path + ": " + where);
    const std::string local = d.contains("local_path") ? text(d.at("local_path"), path, where) : "";
    v.image_path = (fs::path(root) / local / v.label).string();
    std::error_code ec;
    if (!fs::exists(v.image_path, ec) && !index.empty() && !index.find(v.label).empty())
      v.image_path = index.find(v.label);
    if (!fs::exists(v.image_path, ec)) ++missing;
    view_index[key] = int(scene.views.size());
    scene.views.push_back(std::move(v));
  }
  if (scene.views.empty()) throw Error("no view with both a pose and an intrinsic", path);
  if (unposed)
    scene.warnings.push_back(std::to_string(unposed) + " views have no pose or intrinsic (not reconstructed); left out");
  if (missing)
    scene.warnings.push_back(std::to_string(missing) + " images not found (root_path '" + root +
                             "'); pass the image folder to use");
  read_structure(doc, view_index, path, &scene);
  return scene;
}

}  // namespace meshnbv::io
