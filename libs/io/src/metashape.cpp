// Agisoft Metashape "Export Cameras" XML (Agisoft XML; document versions
// 1.2 to 2.x), as documented in the Metashape Professional manual
// (appendix "Camera models") and written by File > Export > Export Cameras:
//
//   <document version="1.5.0"><chunk>
//     <sensors><sensor id="0" type="frame|fisheye">
//       <resolution width= height=/>
//       <calibration class="adjusted"> <resolution/> <f/> <cx/> <cy/> <b1/> <b2/>
//         <k1/>..<k4/> <p1/> <p2/> </calibration></sensor></sensors>
//     <components><component id="0"><transform> (as the chunk's) </transform></component></components>
//     <cameras> [<group>] <camera id= sensor_id= component_id= label=>
//       <transform>16 numbers, row-major 4x4, camera to chunk</transform> </camera> </cameras>
//     <transform><rotation>9</rotation><translation>3</translation><scale>1</scale></transform>
//     <reference>WKT of the chunk's CRS</reference>
//   </chunk></document>
//
// Metashape's frame camera, on (x, y) = (X/Z, Y/Z) in its camera frame
// (x right, y down, z forward: ours):
//   x' = x (1 + K1 r^2 + K2 r^4 + K3 r^6 + K4 r^8) + P1 (r^2 + 2 x^2) + 2 P2 x y
//   y' = y (1 + K1 r^2 + K2 r^4 + K3 r^6 + K4 r^8) + P2 (r^2 + 2 y^2) + 2 P1 x y
//   u = W/2 + cx + x' (f + B1) + y' B2,   v = H/2 + cy + y' f
// with the centre of the top-left pixel at (0.5, 0.5). So, ours:
//   fx = f + B1, fy = f, skew = B2, cx = W/2 + cx - 0.5, cy = H/2 + cy - 0.5,
//   Brown k1..k3 = K1..K3, p1 = P2, p2 = P1 (Metashape's P1, P2 are OpenCV's
//   p2, p1), K4 must be 0 (r^8 is not in our model: an error otherwise).
// Fisheye sensors: (x, y) scaled to the angle theta = atan r, then the same
// polynomial: our fisheye with k1..k4 = K1..K4; P1 = P2 = 0 required.
// Poses: camera-to-world = chunk * component * camera, each a similarity
// [s R | T]; our R is the rotation's transpose, the centre is T.
#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <pugixml.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

using Mat4 = Eigen::Matrix4d;

std::vector<double> xml_numbers(const pugi::xml_node& node, std::size_t expected,
                            const std::string& file, const std::string& what) {
  std::istringstream ss(node.child_value());
  std::vector<double> out;
  std::string token;
  while (ss >> token) out.push_back(parse_double(token, file, -1, what));
  if (out.size() != expected)
    throw Error(what + ": expected " + std::to_string(expected) + " numbers, got " +
                    std::to_string(out.size()),
                file);
  return out;
}

double optional_number(const pugi::xml_node& parent, const char* name, const std::string& file,
                       const std::string& what) {
  const pugi::xml_node n = parent.child(name);
  return n ? xml_numbers(n, 1, file, what + " <" + name + ">")[0] : 0.0;
}

int size_attribute(const pugi::xml_node& node, const char* name, const std::string& file,
                   const std::string& what) {
  const long long v = parse_int(node.attribute(name).value(), file, -1, what + " " + name);
  if (v <= 0 || v > (1 << 30))
    throw Error(what + ": " + name + " must be a positive image size", file);
  return int(v);
}

// The adjusted calibration when there is one, else the first.
pugi::xml_node pick_calibration(const pugi::xml_node& sensor) {
  for (pugi::xml_node c : sensor.children("calibration"))
    if (std::string(c.attribute("class").value()) == "adjusted") return c;
  return sensor.child("calibration");
}

PinholeCamera sensor_camera(const pugi::xml_node& sensor, const std::string& file) {
  const std::string what = "sensor " + std::string(sensor.attribute("id").value()) + " ('" +
                           sensor.attribute("label").value() + "')";
  const std::string type = sensor.attribute("type") ? sensor.attribute("type").value() : "frame";
  if (type != "frame" && type != "fisheye")
    throw Error(what + ": sensor type '" + type + "' is not supported (frame, fisheye)", file);
  const pugi::xml_node cal = pick_calibration(sensor);
  if (!cal) throw Error(what + ": no <calibration> (the sensor was never calibrated)", file);
  if (cal.child("fx") || cal.child("fy"))
    throw Error(what + ": calibration with <fx>/<fy> (PhotoScan before 1.2) is not supported; "
                       "export the cameras again from Metashape",
                file);
  pugi::xml_node res = cal.child("resolution") ? cal.child("resolution") : sensor.child("resolution");
  if (!res) throw Error(what + ": no <resolution>", file);
  PinholeCamera c;
  c.width = size_attribute(res, "width", file, what);
  c.height = size_attribute(res, "height", file, what);
  auto num = [&](const char* name) { return optional_number(cal, name, file, what); };
  if (!cal.child("f")) throw Error(what + ": calibration without <f>", file);
  const double f = num("f"), b1 = num("b1"), b2 = num("b2");
  c.fx = f + b1;
  c.fy = f;
  c.skew = b2;
  c.cx = c.width / 2.0 + num("cx") - 0.5;
  c.cy = c.height / 2.0 + num("cy") - 0.5;
  const double K1 = num("k1"), K2 = num("k2"), K3 = num("k3"), K4 = num("k4");
  const double P1 = num("p1"), P2 = num("p2");
  if (type == "fisheye") {
    if (P1 != 0.0 || P2 != 0.0)
      throw Error(what + ": fisheye with tangential distortion (p1, p2) has no exact equivalent here",
                  file);
    c.lens = LensModel::Fisheye;
    c.k1 = K1, c.k2 = K2, c.k3 = K3, c.k4 = K4;
  } else {
    if (K4 != 0.0)
      throw Error(what + ": k4 (the r^8 term) = " + std::to_string(K4) +
                      " has no exact equivalent here; optimise the cameras without k4",
                  file);
    c.k1 = K1, c.k2 = K2, c.k3 = K3;
    c.p1 = P2;  // Metashape's P2 multiplies 2xy in x': OpenCV's p1
    c.p2 = P1;
  }
  return c;
}

// A <transform> of rotation (9), translation (3) and scale (1), each
// optional, as a 4x4 similarity.
Mat4 similarity(const pugi::xml_node& t, const std::string& file, const std::string& what) {
  Mat4 m = Mat4::Identity();
  if (!t) return m;
  Mat3 R = Mat3::Identity();
  if (t.child("rotation")) {
    const auto r = xml_numbers(t.child("rotation"), 9, file, what + " rotation");
    for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = r[std::size_t(i)];
  }
  const double s = t.child("scale") ? xml_numbers(t.child("scale"), 1, file, what + " scale")[0] : 1.0;
  if (!(s > 0) || !std::isfinite(s)) throw Error(what + ": scale must be positive", file);
  m.topLeftCorner<3, 3>() = s * R;
  if (t.child("translation")) {
    const auto v = xml_numbers(t.child("translation"), 3, file, what + " translation");
    m.topRightCorner<3, 1>() = Vec3(v[0], v[1], v[2]);
  }
  return m;
}

// The camera's pose from its camera-to-world similarity.
void set_pose(const Mat4& to_world, PinholeCamera* cam, const std::string& file,
              const std::string& what) {
  const Mat3 sR = to_world.topLeftCorner<3, 3>();
  const double det = sR.determinant();
  if (!(det > 0) || !std::isfinite(det))
    throw Error(what + ": the camera transform is not a rotation with positive scale", file);
  const Mat3 R = sR / std::cbrt(det);
  cam->R = R.transpose();
  cam->set_center(to_world.topRightCorner<3, 1>());
}

struct Sensors {
  std::map<std::string, pugi::xml_node> nodes;
  std::map<std::string, PinholeCamera> cameras;  // converted when first used
};

void collect_cameras(const pugi::xml_node& parent, std::vector<pugi::xml_node>* out) {
  for (pugi::xml_node n : parent.children()) {
    const std::string name = n.name();
    if (name == "camera") out->push_back(n);
    if (name == "group") collect_cameras(n, out);
  }
}

pugi::xml_node load_chunk(pugi::xml_document* doc, const std::string& path, Scene* scene) {
  const std::string text = read_file(path);
  const pugi::xml_parse_result ok = doc->load_buffer(text.data(), text.size());
  if (!ok) throw Error(std::string("malformed XML: ") + ok.description(), path);
  const pugi::xml_node document = doc->child("document");
  if (!document || !document.child("chunk"))
    throw Error("not a Metashape cameras file (expected <document><chunk>)", path);
  const pugi::xml_node chunk = document.child("chunk");
  if (chunk.next_sibling("chunk"))
    scene->warnings.push_back("the file holds several chunks; only the first is read");
  scene->producer = std::string("Agisoft Metashape (cameras XML, document version ") +
                    document.attribute("version").value() + ")";
  return chunk;
}

std::map<std::string, Mat4> component_transforms(const pugi::xml_node& chunk,
                                                 const std::string& file) {
  std::map<std::string, Mat4> out;
  for (pugi::xml_node c : chunk.child("components").children("component"))
    out[c.attribute("id").value()] = similarity(c.child("transform"), file, "component transform");
  return out;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

}  // namespace

Scene read_metashape(const std::string& path, const std::string& image_dir) {
  Scene scene;
  scene.format = "metashape";
  scene.source = path;
  pugi::xml_document doc;
  const pugi::xml_node chunk = load_chunk(&doc, path, &scene);
  Sensors sensors;
  for (pugi::xml_node s : chunk.child("sensors").children("sensor"))
    sensors.nodes[s.attribute("id").value()] = s;
  const Mat4 chunk_to_world = similarity(chunk.child("transform"), path, "chunk transform");
  // A georeferenced chunk: its transform maps to the geocentric frame of the
  // <reference> CRS's datum (Metashape's world frame); a local one
  // (LOCAL_CS, or no transform) places nothing on Earth.
  const std::string reference = trimmed(chunk.child_value("reference"));
  if (chunk.child("transform") && !reference.empty() && reference.rfind("LOCAL_CS", 0) != 0 &&
      reference.rfind("ENGCRS", 0) != 0 && reference.rfind("ENGINEERINGCRS", 0) != 0) {
    scene.crs = reference;
    scene.crs_geocentric = true;
  }
  const auto components = component_transforms(chunk, path);
  std::vector<pugi::xml_node> cameras;
  collect_cameras(chunk.child("cameras"), &cameras);
  const std::string folder = image_dir.empty() ? fs::path(path).parent_path().string() : image_dir;
  const ImageIndex images(folder.empty() ? "." : folder);
  std::size_t unaligned = 0, missing = 0;
  std::string first_missing;
  for (const pugi::xml_node& node : cameras) {
    const std::string label = node.attribute("label").value();
    const std::string what = "camera " + std::string(node.attribute("id").value()) + " ('" + label + "')";
    if (!node.child("transform")) {
      ++unaligned;
      continue;
    }
    const std::string sensor_id = node.attribute("sensor_id").value();
    if (!sensors.nodes.count(sensor_id))
      throw Error(what + " refers to sensor " + sensor_id + ", which the file does not define", path);
    if (!sensors.cameras.count(sensor_id))
      sensors.cameras[sensor_id] = sensor_camera(sensors.nodes[sensor_id], path);
    View view;
    view.label = label;
    view.camera = sensors.cameras[sensor_id];
    const auto t = xml_numbers(node.child("transform"), 16, path, what + " transform");
    Mat4 to_chunk;
    for (int i = 0; i < 16; ++i) to_chunk(i / 4, i % 4) = t[std::size_t(i)];
    const auto component = components.find(node.attribute("component_id").value());
    const Mat4 to_world = chunk_to_world *
                          (component == components.end() ? Mat4::Identity() : component->second) *
                          to_chunk;
    set_pose(to_world, &view.camera, path, what);
    view.image_path = images.find(label);
    if (view.image_path.empty() && missing++ == 0) first_missing = label;
    scene.views.push_back(std::move(view));
  }
  if (scene.views.empty())
    throw Error("no aligned camera (" + std::to_string(cameras.size()) +
                    " cameras, none with a <transform>)",
                path);
  if (unaligned)
    scene.warnings.push_back(std::to_string(unaligned) +
                             " cameras are not aligned (no <transform>) and were left out");
  if (missing)
    scene.warnings.push_back(std::to_string(missing) + " images not found under " + folder +
                             " (e.g. '" + first_missing + "'); pass the image folder to use");
  return scene;
}

}  // namespace meshnbv::io
