// MeshLab project (.mlp) reader and writer. Camera conversion between VCG's
// Shot and our PinholeCamera (docs/conventions.md, derived from vcglib's
// Shot::ConvertWorldToCameraCoordinates and Camera::Project/LocalToViewportPx):
//   VCG: q = Rv (X - C), depth = -q.z, px = fx q.x / depth + CenterPx.x,
//        py = fy q.y / depth + CenterPx.y (origin at the image's bottom-left
//        corner, y up), C = -TranslationVector, fx = FocalMm / PixelSizeMm.x.
//   Ours: R = diag(1, -1, -1) Rv, t = -R C, cx = CenterPx.x - 0.5,
//        cy = H - CenterPx.y - 0.5 (pixel centres at integers, y down).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <Eigen/Geometry>
#include <pugixml.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace fs = std::filesystem;

namespace meshnbv::io {
namespace {

// PixelSizeMm we write; any positive value gives the same pixels.
constexpr double kWrittenPixelSizeMm = 0.0369161;

std::vector<double> mlp_numbers(const char* text, std::size_t expected, const std::string& file,
                            const std::string& what) {
  std::istringstream ss(text ? text : "");
  std::vector<double> out;
  std::string token;
  while (ss >> token) out.push_back(parse_double(token, file, -1, what));
  if (out.size() < expected)
    throw Error(what + ": expected " + std::to_string(expected) + " numbers, got " +
                    std::to_string(out.size()),
                file);
  return out;
}

// False when `in` holds a character outside base64 and whitespace.
bool base64_decode(const std::string& in, std::string* out) {
  static const std::string chars =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  // Only the low 6 + 8 bits matter; unsigned and masked so that long input
  // never shifts bits out of a signed int (undefined behaviour).
  unsigned value = 0;
  int bits = -8;
  for (char c : in) {
    if (c == '=') break;
    auto pos = chars.find(c);
    if (pos == std::string::npos) {
      if (std::isspace(static_cast<unsigned char>(c))) continue;
      return false;
    }
    value = ((value << 6) | static_cast<unsigned>(pos)) & 0x3FFFu;
    bits += 6;
    if (bits >= 0) {
      out->push_back(char((value >> bits) & 0xFF));
      bits -= 8;
    }
  }
  return true;
}

// BinaryData="1": MeshLab stores raw float/int arrays in base64.
template <typename T>
std::vector<double> binary_numbers(const char* text, std::size_t count, const std::string& file,
                                   const std::string& what) {
  std::string bytes;
  if (!base64_decode(text ? text : "", &bytes))
    throw Error(what + ": invalid base64 data (BinaryData=\"1\")", file);
  if (bytes.size() < count * sizeof(T))
    throw Error(what + ": binary data too short", file);
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    out[i] = static_cast<double>(v);
  }
  return out;
}

PinholeCamera camera_from_vcg(const pugi::xml_node& node, const std::string& file,
                              const std::string& label) {
  const bool binary = node.attribute("BinaryData").as_int(0) == 1;
  auto get = [&](const char* name, std::size_t count, bool ints = false) {
    const pugi::xml_attribute attr = node.attribute(name);
    if (!attr) throw Error(std::string("VCGCamera has no ") + name, file, -1, "raster '" + label + "'");
    const std::string what = "raster '" + label + "' " + name;
    if (binary)
      return ints ? binary_numbers<int>(attr.value(), count, file, what)
                  : binary_numbers<float>(attr.value(), count, file, what);
    return mlp_numbers(attr.value(), count, file, what);
  };
  const auto tra = get("TranslationVector", 3);
  const auto rot = get("RotationMatrix", 16);
  const auto focal = get("FocalMm", 1);
  const auto pixel = get("PixelSizeMm", 2);
  const auto viewport = get("ViewportPx", 2, true);
  const auto center = get("CenterPx", 2);
  std::vector<double> lens{0, 0};
  if (node.attribute("LensDistortion")) lens = get("LensDistortion", 2);
  const std::string element = "raster '" + label + "'";
  if (node.attribute("CameraType").as_int(0) != 0)
    throw Error("orthographic VCGCamera (CameraType != 0) is not supported", file, -1, element);
  if (lens[0] != 0.0 || lens[1] != 0.0)
    throw Error("non-zero LensDistortion is not supported (VCG's distortion model is not a radial "
                "polynomial); undistort the images and set it to 0 0",
                file, -1, element);
  if (!(pixel[0] > 0) || !(pixel[1] > 0))
    throw Error("PixelSizeMm must be positive", file, -1, element);
  // Checked before the cast: converting 1e300 to int is undefined behaviour.
  for (double v : {viewport[0], viewport[1]})
    if (!(v >= 1 && v <= (1 << 30))) {
      std::ostringstream ss;
      ss << "ViewportPx must be an image size in [1, 2^30], got " << viewport[0] << " "
         << viewport[1];
      throw Error(ss.str(), file, -1, element);
    }
  PinholeCamera cam;
  cam.width = static_cast<int>(viewport[0]);
  cam.height = static_cast<int>(viewport[1]);
  cam.fx = focal[0] / pixel[0];
  cam.fy = focal[0] / pixel[1];
  cam.cx = center[0] - 0.5;
  cam.cy = cam.height - center[1] - 0.5;
  Mat3 rv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rv(r, c) = rot[4 * r + c];
  cam.R.row(0) = rv.row(0);
  cam.R.row(1) = -rv.row(1);
  cam.R.row(2) = -rv.row(2);
  cam.set_center(Vec3(-tra[0], -tra[1], -tra[2]));
  cam.check(file + ": " + element);
  return cam;
}

Eigen::Matrix4d read_matrix(const pugi::xml_node& node, const std::string& file) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (!node) return m;
  const auto v = mlp_numbers(node.child_value(), 16, file, "MLMatrix44");
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = v[4 * r + c];
  return m;
}

std::string fmt(double v) {
  std::ostringstream ss;
  ss.precision(17);
  ss << v;
  return ss.str();
}

}  // namespace

Scene read_mlp(const std::string& path) {
  const std::string text = read_file(path);
  pugi::xml_document doc;
  pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size());
  if (!parsed) {
    // pugixml reports a byte offset; turn it into a line number.
    long line = 1 + static_cast<long>(std::count(text.begin(),
                                                 text.begin() + std::min<std::ptrdiff_t>(
                                                     parsed.offset, std::ptrdiff_t(text.size())),
                                                 '\n'));
    throw Error(std::string("malformed XML: ") + parsed.description(), path, line);
  }
  pugi::xml_node project = doc.child("MeshLabProject");
  if (!project) throw Error("not a MeshLab project (no <MeshLabProject> element)", path);
  const std::string base = fs::path(path).parent_path().string();

  Scene scene;
  scene.source = path;
  scene.format = "mlp";
  int mesh_count = 0;
  for (pugi::xml_node m : project.child("MeshGroup").children("MLMesh")) {
    const char* filename = m.attribute("filename").value();
    if (!*filename) throw Error("MLMesh without a filename", path);
    const std::string mesh_file = resolve(filename, base);
    TriangleMesh part = read_mesh(mesh_file);
    const Eigen::Matrix4d tr = read_matrix(m.child("MLMatrix44"), path);
    if (!tr.isIdentity(0)) {
      for (auto& v : part.vertices) v = (tr * v.homogeneous()).hnormalized();
    }
    if (mesh_count++ == 0) {
      scene.mesh = std::move(part);
      scene.mesh_path = mesh_file;
    } else {
      scene.mesh.append(part);
      scene.warnings.push_back("merged mesh layer '" + std::string(filename) + "'");
    }
  }
  if (mesh_count > 1) scene.mesh_path.clear();  // no single file holds the merged mesh

  int index = 0;
  for (pugi::xml_node r : project.child("RasterGroup").children("MLRaster")) {
    View view;
    view.label = r.attribute("label").value();
    if (view.label.empty()) view.label = "raster_" + std::to_string(index);
    pugi::xml_node cam = r.child("VCGCamera");
    if (!cam) throw Error("raster has no VCGCamera", path, -1, "raster '" + view.label + "'");
    view.camera = camera_from_vcg(cam, path, view.label);
    // Only the first <Plane> is used, as MeshLab does.
    pugi::xml_node plane = r.child("Plane");
    if (plane && *plane.attribute("fileName").value())
      view.image_path = resolve(plane.attribute("fileName").value(), base);
    scene.views.push_back(std::move(view));
    ++index;
  }
  return scene;
}

std::string mlp_unsupported_reason(const Scene& scene) {
  for (const auto& v : scene.views)
    if (v.camera.has_distortion())
      return "view '" + v.label + "' has a lens (" + v.camera.lens_description() +
             ") that a MeshLab project cannot represent; undistort first or write JSON";
  return {};
}

void write_mlp(const Scene& scene, const std::string& path, const std::string& mesh_file,
               bool overwrite) {
  for (const auto& v : scene.views) {
    v.camera.check("view '" + v.label + "'");
    v.image_file("a MeshLab project (.mlp)");
  }
  const std::string unsupported = mlp_unsupported_reason(scene);
  if (!unsupported.empty()) throw Error(unsupported, path);
  const std::string base = fs::path(path).parent_path().string();
  pugi::xml_document doc;
  doc.append_child(pugi::node_doctype).set_value("MeshLabDocument");
  pugi::xml_node project = doc.append_child("MeshLabProject");
  pugi::xml_node meshes = project.append_child("MeshGroup");
  if (!mesh_file.empty()) {
    pugi::xml_node m = meshes.append_child("MLMesh");
    const std::string rel = relative_to(mesh_file, base);
    m.append_attribute("label") = fs::path(mesh_file).filename().string().c_str();
    m.append_attribute("filename") = rel.c_str();
    m.append_attribute("visible") = "1";
    m.append_child("MLMatrix44")
        .append_child(pugi::node_pcdata)
        .set_value("\n1 0 0 0 \n0 1 0 0 \n0 0 1 0 \n0 0 0 1 \n");
  }
  pugi::xml_node rasters = project.append_child("RasterGroup");
  for (const auto& v : scene.views) {
    const PinholeCamera& c = v.camera;
    pugi::xml_node r = rasters.append_child("MLRaster");
    r.append_attribute("label") = v.label.c_str();
    pugi::xml_node cam = r.append_child("VCGCamera");
    const Vec3 center = c.center();
    cam.append_attribute("TranslationVector") =
        (fmt(-center.x()) + " " + fmt(-center.y()) + " " + fmt(-center.z()) + " 1").c_str();
    std::string rot;
    for (int row = 0; row < 3; ++row) {
      const double sign = row == 0 ? 1.0 : -1.0;
      for (int col = 0; col < 3; ++col) rot += fmt(sign * c.R(row, col)) + " ";
      rot += "0 ";
    }
    rot += "0 0 0 1 ";
    cam.append_attribute("RotationMatrix") = rot.c_str();
    cam.append_attribute("CameraType") = "0";
    cam.append_attribute("BinaryData") = "0";
    const double focal_mm = c.fx * kWrittenPixelSizeMm;
    cam.append_attribute("FocalMm") = fmt(focal_mm).c_str();
    cam.append_attribute("LensDistortion") = "0 0";
    cam.append_attribute("PixelSizeMm") =
        (fmt(kWrittenPixelSizeMm) + " " + fmt(focal_mm / c.fy)).c_str();
    cam.append_attribute("ViewportPx") =
        (std::to_string(c.width) + " " + std::to_string(c.height)).c_str();
    cam.append_attribute("CenterPx") =
        (fmt(c.cx + 0.5) + " " + fmt(c.height - c.cy - 0.5)).c_str();
    if (v.has_image()) {
      pugi::xml_node plane = r.append_child("Plane");
      plane.append_attribute("semantic") = "1";
      plane.append_attribute("fileName") = relative_to(v.image_file("a MeshLab project (.mlp)"), base).c_str();
    }
  }
  write_atomically(path, [&](std::ostream& out) { doc.save(out, " "); }, overwrite);
}

}  // namespace meshnbv::io
