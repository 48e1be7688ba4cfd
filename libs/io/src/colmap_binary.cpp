// COLMAP binary models (COLMAP 3.x, src/base/reconstruction.cc), all
// little-endian:
//   cameras.bin:  uint64 count; per camera: uint32 CAMERA_ID, int32 MODEL_ID,
//                 uint64 WIDTH, uint64 HEIGHT, double PARAMS[n(MODEL_ID)]
//   images.bin:   uint64 count; per image: uint32 IMAGE_ID, double QW QX QY QZ,
//                 double TX TY TZ, uint32 CAMERA_ID, NAME (bytes up to '\0'),
//                 uint64 n2d, n2d x (double X, double Y, uint64 POINT3D_ID)
//   points3D.bin: uint64 count; per point: uint64 POINT3D_ID, double X Y Z,
//                 uint8 R G B, double ERROR, uint64 track length,
//                 per element: uint32 IMAGE_ID, uint32 POINT2D_IDX
// The same conventions as the text files (colmap.cpp).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "colmap_cameras.h"
#include "colmap_model.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"

namespace fs = std::filesystem;

namespace meshnbv::io::colmap {
namespace {

class ByteReader {
 public:
  ByteReader(std::string bytes, std::string file) : bytes_(std::move(bytes)), file_(std::move(file)) {}

  template <typename T>
  T read(const char* what) {
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));  // little-endian hosts only (x86, arm64)
    pos_ += sizeof(T);
    return value;
  }
  double read_double(const char* what) {
    const double v = read<double>(what);
    if (!std::isfinite(v)) fail(std::string("non-finite ") + what);
    return v;
  }
  std::string read_name() {
    const std::size_t end = bytes_.find('\0', pos_);
    if (end == std::string::npos) fail("truncated: image name without its terminating NUL");
    std::string name = bytes_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return name;
  }
  // A count of records of at least `record_bytes` each that must fit in
  // what is left of the file.
  std::uint64_t read_count(std::size_t record_bytes, const char* what) {
    const std::uint64_t n = read<std::uint64_t>(what);
    if (n > (bytes_.size() - pos_) / record_bytes)
      fail(std::string("truncated or corrupt: ") + what + " = " + std::to_string(n) +
           " does not fit in the " + std::to_string(bytes_.size() - pos_) + " bytes left");
    return n;
  }
  void expect_end() {
    if (pos_ != bytes_.size())
      fail(std::to_string(bytes_.size() - pos_) + " unexpected bytes after the last record");
  }
  [[noreturn]] void fail(const std::string& reason) const {
    throw Error(reason + " (at byte " + std::to_string(pos_) + ")", file_);
  }

 private:
  void need(std::size_t n, const char* what) {
    if (bytes_.size() - pos_ < n)
      fail(std::string("truncated: the file ends inside ") + what);
  }
  std::string bytes_;
  std::string file_;
  std::size_t pos_ = 0;
};

int binary_image_size(std::uint64_t v, const char* what, ByteReader& in) {
  if (v == 0 || v > (1u << 30))
    in.fail(std::string(what) + " must be a positive image size, got " + std::to_string(v));
  return static_cast<int>(v);
}

Camera read_camera(ByteReader& in, long long* id) {
  *id = in.read<std::uint32_t>("CAMERA_ID");
  const int model_id = in.read<std::int32_t>("MODEL_ID");
  const CameraModelSpec* spec = find_model(model_id);
  if (!spec)
    in.fail("camera " + std::to_string(*id) + ": unknown camera model id " +
            std::to_string(model_id) + " (COLMAP 3.8 models are 0..10: " + model_names() + ")");
  Camera cam;
  cam.model = spec->name;
  const int width = binary_image_size(in.read<std::uint64_t>("WIDTH"), "WIDTH", in);
  const int height = binary_image_size(in.read<std::uint64_t>("HEIGHT"), "HEIGHT", in);
  std::vector<double> params;
  for (std::size_t i = 0; i < spec->num_params; ++i) params.push_back(in.read_double("PARAMS"));
  try {
    cam.intrinsics = camera_from_params(*spec, params);
    cam.intrinsics.width = width;
    cam.intrinsics.height = height;
    cam.intrinsics.check("camera " + std::to_string(*id) + " (" + spec->name + ")");
  } catch (const Error& e) {
    in.fail(e.reason());
  }
  return cam;
}

Image read_image(ByteReader& in) {
  Image image;
  image.id = in.read<std::uint32_t>("IMAGE_ID");
  double q[4];
  for (double& v : q) v = in.read_double("QVEC");
  for (int k = 0; k < 3; ++k) image.t(k) = in.read_double("TVEC");
  Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
  if (!(quat.norm() > 1e-12)) in.fail("image " + std::to_string(image.id) + ": zero quaternion");
  image.R = quat.normalized().toRotationMatrix();
  image.camera_id = in.read<std::uint32_t>("CAMERA_ID");
  image.name = in.read_name();
  const std::uint64_t n = in.read_count(24, "number of 2-D points");
  image.points2d.reserve(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    const double x = in.read_double("POINTS2D x");
    const double y = in.read_double("POINTS2D y");
    (void)in.read<std::uint64_t>("POINT3D_ID");
    image.points2d.emplace_back(x, y);
  }
  return image;
}

Point read_point(ByteReader& in) {
  Point p;
  (void)in.read<std::uint64_t>("POINT3D_ID");
  for (int k = 0; k < 3; ++k) p.position(k) = in.read_double("XYZ");
  for (int k = 0; k < 3; ++k) (void)in.read<std::uint8_t>("RGB");
  (void)in.read<double>("ERROR");
  const std::uint64_t n = in.read_count(8, "track length");
  p.track.reserve(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    const long long image_id = in.read<std::uint32_t>("track IMAGE_ID");
    const long long idx = in.read<std::uint32_t>("track POINT2D_IDX");
    p.track.emplace_back(image_id, idx);
  }
  return p;
}

}  // namespace

Model read_binary_model(const std::string& folder) {
  Model model;
  model.cameras_file = (fs::path(folder) / "cameras.bin").string();
  model.images_file = (fs::path(folder) / "images.bin").string();
  model.points_file = (fs::path(folder) / "points3D.bin").string();
  ByteReader cams(read_file(model.cameras_file), model.cameras_file);
  const std::uint64_t num_cameras = cams.read_count(24, "number of cameras");
  if (num_cameras == 0) cams.fail("no camera defined");
  for (std::uint64_t i = 0; i < num_cameras; ++i) {
    long long id = 0;
    Camera cam = read_camera(cams, &id);
    if (!model.cameras.emplace(id, cam).second)
      cams.fail("camera " + std::to_string(id) + " is defined twice");
  }
  cams.expect_end();

  ByteReader imgs(read_file(model.images_file), model.images_file);
  const std::uint64_t num_images = imgs.read_count(73, "number of images");
  if (num_images == 0) imgs.fail("no image listed");
  for (std::uint64_t i = 0; i < num_images; ++i) model.images.push_back(read_image(imgs));
  imgs.expect_end();

  if (is_file(model.points_file)) {
    model.has_points = true;
    ByteReader pts(read_file(model.points_file), model.points_file);
    const std::uint64_t num_points = pts.read_count(51, "number of 3-D points");
    model.points.reserve(num_points);
    for (std::uint64_t i = 0; i < num_points; ++i) model.points.push_back(read_point(pts));
    pts.expect_end();
  }
  return model;
}

}  // namespace meshnbv::io::colmap
