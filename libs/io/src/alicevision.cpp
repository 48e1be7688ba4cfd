// AliceVision / Meshroom sfm.json and cameras.sfm (JSON written by
// boost::property_tree: numbers are mostly strings), file versions 1.0 to 1.2.x:
//   "version": ["1", "2", "5"]
//   "views": [{ "viewId", "poseId", "intrinsicId", "path", "width", "height" }]
//   "intrinsics": [{ "intrinsicId", "width", "height", "type", "principalPoint": [2],
//                    focal (below), "distortionParams": [...] }]
//   "poses": [{ "poseId", "pose": { "transform": { "rotation": [9], "center": [3] }}}]
//   "structure": [{ "X": [3], "observations": [{ "observationId": viewId, "x": [2] }]}]
// Conventions (aliceVision/sfmDataIO/jsonIO.cpp, geometry/Pose3.hpp):
// - rotation: the 9 entries of R (world to camera, x_cam = R (X - C)) in
//   Eigen's storage order, i.e. COLUMN-major; center C.
// - principal point: absolute before version 1.2.1, else an offset from
//   the image centre (W/2, H/2).
// - focal: "pxFocalLength" (one number) before 1.2.0; [fx, fy] before 1.2.2;
//   then "focalLength" in mm with "sensorWidth": fx = focalLength / sensorWidth * W
//   and fy = fx / pixelRatio before 1.2.5, fy = fx * pixelRatio from 1.2.5.
// - pixels: integer coordinates taken as pixel centres (as OpenMVG, which
//   AliceVision forked), nothing shifted.
// - lenses: "pinhole"; "radial1" (k1); "radial3" (k1 k2 k3); "brown"
//   (k1 k2 k3 t1 t2, t1 and t2 being OpenCV's p1, p2); "fisheye4" (k1..k4,
//   OpenCV's fisheye). Other types are an Error naming the type.
// Views in a rig (rigId) are an Error: their pose is relative to the rig's.
#include <array>
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
using Version = std::array<long long, 3>;

Version file_version(const json& doc, const std::string& file) {
  Version v{1, 0, 0};
  if (!doc.contains("version")) return v;
  const json& j = doc.at("version");
  if (!j.is_array() || j.size() != 3) throw Error("\"version\" must be 3 numbers", file);
  for (std::size_t i = 0; i < 3; ++i) v[i] = integer(j[i], file, "version");
  return v;
}

void set_focal(const json& d, const Version& version, PinholeCamera* c, const std::string& file,
               const std::string& where) {
  if (version < Version{1, 2, 0}) {
    c->fx = c->fy = number(member(d, "pxFocalLength", file, where), file, where + " pxFocalLength");
  } else if (version < Version{1, 2, 2}) {
    const auto f = numbers(member(d, "pxFocalLength", file, where), 2, file, where + " pxFocalLength");
    c->fx = f[0], c->fy = f[1];
  } else {
    const double fmm = number(member(d, "focalLength", file, where), file, where + " focalLength");
    const double sensor = number(member(d, "sensorWidth", file, where), file, where + " sensorWidth");
    const double ratio = d.contains("pixelRatio") ? number(d.at("pixelRatio"), file, where) : 1.0;
    if (!(sensor > 0) || !(ratio > 0)) throw Error("sensorWidth and pixelRatio must be positive", file, -1, where);
    c->fx = fmm / sensor * c->width;
    c->fy = version < Version{1, 2, 5} ? c->fx / ratio : c->fx * ratio;
  }
}

void set_lens(const std::string& type, const std::vector<double>& d, PinholeCamera* c,
              const std::string& file, const std::string& where) {
  auto need = [&](std::size_t n) {
    if (d.size() != n)
      throw Error("type " + type + " takes " + std::to_string(n) + " distortionParams, got " +
                      std::to_string(d.size()),
                  file, -1, where);
  };
  if (type == "pinhole") {
    need(0);
  } else if (type == "radial1") {
    need(1);
    c->k1 = d[0];
  } else if (type == "radial3") {
    need(3);
    c->k1 = d[0], c->k2 = d[1], c->k3 = d[2];
  } else if (type == "brown") {
    need(5);
    set_brown(d, c);
  } else if (type == "fisheye4") {
    need(4);
    c->lens = LensModel::Fisheye;
    c->k1 = d[0], c->k2 = d[1], c->k3 = d[2], c->k4 = d[3];
  } else {
    throw Error("intrinsic type '" + type +
                    "' is not supported (pinhole, radial1, radial3, brown, fisheye4)",
                file, -1, where);
  }
}

std::map<std::string, PinholeCamera> read_intrinsics(const json& doc, const Version& version,
                                                     const std::string& file) {
  std::map<std::string, PinholeCamera> out;
  const json& list = member(doc, "intrinsics", file, "");
  if (!list.is_array()) throw Error("\"intrinsics\" must be an array", file);
  for (const json& d : list) {
    const std::string id = text(member(d, "intrinsicId", file, "intrinsic"), file, "intrinsicId");
    const std::string where = "intrinsic " + id;
    PinholeCamera c;
    c.width = image_size(member(d, "width", file, where), file, where + " width");
    c.height = image_size(member(d, "height", file, where), file, where + " height");
    set_focal(d, version, &c, file, where);
    auto pp = numbers(member(d, "principalPoint", file, where), 2, file, where + " principalPoint");
    if (!(version < Version{1, 2, 1})) pp[0] += c.width / 2.0, pp[1] += c.height / 2.0;
    c.cx = pp[0];
    c.cy = pp[1];
    const std::string type = text(member(d, "type", file, where), file, where + " type");
    const auto dist = d.contains("distortionParams")
                          ? numbers(d.at("distortionParams"), 0, file, where + " distortionParams")
                          : std::vector<double>();
    set_lens(type, dist, &c, file, where);
    c.check(file + ": " + where);
    out[id] = c;
  }
  return out;
}

std::map<std::string, std::pair<Mat3, Vec3>> read_poses(const json& doc, const std::string& file) {
  std::map<std::string, std::pair<Mat3, Vec3>> out;
  const json& list = doc.contains("poses") ? doc.at("poses") : json::array();
  if (!list.is_array()) throw Error("\"poses\" must be an array", file);
  for (const json& p : list) {
    const std::string id = text(member(p, "poseId", file, "pose"), file, "poseId");
    const std::string where = "pose " + id;
    const json& t = member(member(p, "pose", file, where), "transform", file, where);
    const auto r = numbers(member(t, "rotation", file, where), 9, file, where + " rotation");
    const auto c = numbers(member(t, "center", file, where), 3, file, where + " center");
    Mat3 R;
    for (int i = 0; i < 9; ++i) R(i % 3, i / 3) = r[std::size_t(i)];  // column-major
    out[id] = {R, Vec3(c[0], c[1], c[2])};
  }
  return out;
}

void read_structure(const json& doc, const std::map<std::string, int>& view_index,
                    const std::string& file, Scene* scene) {
  if (!doc.contains("structure")) return;
  const json& list = doc.at("structure");
  if (!list.is_array()) throw Error("\"structure\" must be an array", file);
  for (const json& l : list) {
    SparsePoint p;
    const auto X = numbers(member(l, "X", file, "landmark"), 3, file, "landmark X");
    p.position = Vec3(X[0], X[1], X[2]);
    if (l.contains("observations")) {
      if (!l.at("observations").is_array()) throw Error("\"observations\" must be an array", file);
      for (const json& o : l.at("observations")) {
        const std::string view = text(member(o, "observationId", file, "observation"), file, "observationId");
        const auto it = view_index.find(view);
        if (it == view_index.end() || !o.contains("x")) continue;
        const auto x = numbers(o.at("x"), 2, file, "observation x");
        p.observations.emplace_back(it->second, Vec2(x[0], x[1]));
      }
    }
    scene->sparse_points.push_back(std::move(p));
  }
}

}  // namespace

Scene read_alicevision(const std::string& path, const std::string& image_dir) {
  const json doc = parse(path);
  if (!doc.is_object() || !doc.contains("views") || !doc.contains("intrinsics"))
    throw Error("not an AliceVision sfm file (expected \"views\" and \"intrinsics\")", path);
  const Version version = file_version(doc, path);
  Scene scene;
  scene.format = "alicevision";
  scene.source = path;
  scene.producer = "AliceVision / Meshroom (sfm JSON, version " + std::to_string(version[0]) + "." +
                   std::to_string(version[1]) + "." + std::to_string(version[2]) + ")";
  const auto intrinsics = read_intrinsics(doc, version, path);
  const auto poses = read_poses(doc, path);
  const ImageIndex index = image_dir.empty() ? ImageIndex() : ImageIndex(image_dir);
  const json& views = doc.at("views");
  if (!views.is_array()) throw Error("\"views\" must be an array", path);
  std::map<std::string, int> view_index;
  std::size_t unposed = 0, missing = 0;
  for (const json& d : views) {
    const std::string id = text(member(d, "viewId", path, "view"), path, "viewId");
    const std::string where = "view " + id;
    if (d.contains("rigId"))
      throw Error("views in a camera rig are not supported (their pose is relative to the rig)", path, -1, where);
    const auto intr = d.contains("intrinsicId") ? intrinsics.find(text(d.at("intrinsicId"), path, where)) : intrinsics.end();
    const auto pose = d.contains("poseId") ? poses.find(text(d.at("poseId"), path, where)) : poses.end();
    if (intr == intrinsics.end() || pose == poses.end()) {
      ++unposed;
      continue;
    }
    View v;
    const std::string image = text(member(d, "path", path, where), path, where + " path");
    v.label = fs::path(image).filename().string();
    v.camera = intr->second;
    v.camera.R = pose->second.first;
    v.camera.set_center(pose->second.second);
    v.camera.check(path + ": " + where);
    v.image_path = image;
    std::error_code ec;
    if (!index.empty() && !index.find(image).empty()) v.image_path = index.find(image);
    if (!fs::exists(v.image_path, ec)) ++missing;
    view_index[id] = int(scene.views.size());
    scene.views.push_back(std::move(v));
  }
  if (scene.views.empty()) throw Error("no view with both a pose and an intrinsic", path);
  if (unposed)
    scene.warnings.push_back(std::to_string(unposed) + " views have no pose or intrinsic (not reconstructed); left out");
  if (missing)
    scene.warnings.push_back(std::to_string(missing) + " images not found at their recorded paths; pass the image folder to use");
  read_structure(doc, view_index, path, &scene);
  return scene;
}

}  // namespace meshnbv::io
