// COLMAP 3.8 camera models (src/base/camera_models.h of COLMAP 3.8), in its
// own words, and how each maps to ours:
// - every model: pixel = f * distorted normalised + c, with COLMAP's pixel
//   origin half a pixel off ours (cx_ours = cx - 0.5);
// - SIMPLE_RADIAL, RADIAL: x (1 + k r^2 [+ k2 r^4]): Brown k1 (k2);
// - OPENCV: radial k1, k2 + tangential p1, p2 as OpenCV: Brown;
// - FULL_OPENCV: (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//   + tangential: Brown with k1..k6, p1, p2;
// - OPENCV_FISHEYE, SIMPLE_RADIAL_FISHEYE (k), RADIAL_FISHEYE (k1, k2):
//   theta_d = theta (1 + k1 th^2 + ...), theta = atan r: our fisheye;
// - THIN_PRISM_FISHEYE: (theta / r) (x, y), then k1..k4 radial in theta^2
//   (= our fisheye) plus tangential p1, p2 and thin prism sx1, sy1 on those
//   angles: exact only when p1 = p2 = sx1 = sy1 = 0;
// - FOV: atan-based with omega: exact only for omega = 0 (a pinhole).
#include "colmap_cameras.h"

#include "meshnbv/error.h"

namespace meshnbv::io::colmap {
namespace {

constexpr CameraModelSpec kModels[] = {
    {0, "SIMPLE_PINHOLE", 3, "f cx cy"},
    {1, "PINHOLE", 4, "fx fy cx cy"},
    {2, "SIMPLE_RADIAL", 4, "f cx cy k"},
    {3, "RADIAL", 5, "f cx cy k1 k2"},
    {4, "OPENCV", 8, "fx fy cx cy k1 k2 p1 p2"},
    {5, "OPENCV_FISHEYE", 8, "fx fy cx cy k1 k2 k3 k4"},
    {6, "FULL_OPENCV", 12, "fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6"},
    {7, "FOV", 5, "fx fy cx cy omega"},
    {8, "SIMPLE_RADIAL_FISHEYE", 4, "f cx cy k"},
    {9, "RADIAL_FISHEYE", 5, "f cx cy k1 k2"},
    {10, "THIN_PRISM_FISHEYE", 12, "fx fy cx cy k1 k2 p1 p2 k3 k4 sx1 sy1"},
};

bool one_focal(const std::string& name) {
  return name == "SIMPLE_PINHOLE" || name == "SIMPLE_RADIAL" || name == "RADIAL" ||
         name == "SIMPLE_RADIAL_FISHEYE" || name == "RADIAL_FISHEYE";
}

// The parameters after the principal point, by model.
void set_lens(const std::string& name, const double* e, PinholeCamera* c) {
  if (name == "SIMPLE_RADIAL") {
    c->k1 = e[0];
  } else if (name == "RADIAL") {
    c->k1 = e[0], c->k2 = e[1];
  } else if (name == "OPENCV" || name == "FULL_OPENCV") {
    c->k1 = e[0], c->k2 = e[1], c->p1 = e[2], c->p2 = e[3];
    if (name == "FULL_OPENCV") c->k3 = e[4], c->k4 = e[5], c->k5 = e[6], c->k6 = e[7];
  } else if (name == "OPENCV_FISHEYE" || name == "THIN_PRISM_FISHEYE") {
    c->lens = LensModel::Fisheye;
    const bool prism = name == "THIN_PRISM_FISHEYE";
    c->k1 = e[0], c->k2 = e[1];
    c->k3 = prism ? e[4] : e[2];
    c->k4 = prism ? e[5] : e[3];
    if (prism && (e[2] != 0.0 || e[3] != 0.0 || e[6] != 0.0 || e[7] != 0.0))
      throw Error("camera model THIN_PRISM_FISHEYE with p1, p2, sx1 or sy1 non-zero has no exact "
                  "equivalent here (supported: that model with them 0, OPENCV_FISHEYE); run "
                  "`colmap image_undistorter` to get a PINHOLE model");
  } else if (name == "SIMPLE_RADIAL_FISHEYE" || name == "RADIAL_FISHEYE") {
    c->lens = LensModel::Fisheye;
    c->k1 = e[0];
    if (name == "RADIAL_FISHEYE") c->k2 = e[1];
  } else if (name == "FOV" && e[0] != 0.0) {
    throw Error("camera model FOV (omega = " + std::to_string(e[0]) +
                ") has no exact equivalent here; run `colmap image_undistorter` to get a PINHOLE "
                "model");
  }
}

}  // namespace

const CameraModelSpec* find_model(const std::string& name) {
  for (const auto& m : kModels)
    if (name == m.name) return &m;
  return nullptr;
}

const CameraModelSpec* find_model(int id) {
  for (const auto& m : kModels)
    if (id == m.id) return &m;
  return nullptr;
}

std::string model_names() {
  std::string names;
  for (const auto& m : kModels) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

PinholeCamera camera_from_params(const CameraModelSpec& model, const std::vector<double>& p) {
  if (p.size() != model.num_params)
    throw Error("camera model " + std::string(model.name) + " takes " +
                std::to_string(model.num_params) + " parameters (" + model.params + "), got " +
                std::to_string(p.size()));
  PinholeCamera cam;
  const bool single = one_focal(model.name);
  const std::size_t c = single ? 1 : 2;  // index of cx
  cam.fx = p[0];
  cam.fy = single ? p[0] : p[1];
  cam.cx = p[c] - kPixelOffset;
  cam.cy = p[c + 1] - kPixelOffset;
  set_lens(model.name, p.data() + c + 2, &cam);
  return cam;
}

const CameraModelSpec& model_for(const PinholeCamera& c, std::vector<double>* params) {
  if (c.skew != 0.0)
    throw Error("a camera with skew (" + std::to_string(c.skew) +
                " px) cannot be written as COLMAP, whose camera models have none; write JSON");
  const double cx = c.cx + kPixelOffset, cy = c.cy + kPixelOffset;
  if (c.lens == LensModel::Fisheye) {
    *params = {c.fx, c.fy, cx, cy, c.k1, c.k2, c.k3, c.k4};
    return *find_model("OPENCV_FISHEYE");
  }
  if (!c.has_distortion()) {
    *params = {c.fx, c.fy, cx, cy};
    return *find_model("PINHOLE");
  }
  const bool rational = c.k3 != 0.0 || c.k4 != 0.0 || c.k5 != 0.0 || c.k6 != 0.0;
  if (rational) {
    *params = {c.fx, c.fy, cx, cy, c.k1, c.k2, c.p1, c.p2, c.k3, c.k4, c.k5, c.k6};
    return *find_model("FULL_OPENCV");
  }
  if (c.fx == c.fy && c.p1 == 0.0 && c.p2 == 0.0) {
    *params = {c.fx, cx, cy, c.k1, c.k2};
    return *find_model("RADIAL");
  }
  *params = {c.fx, c.fy, cx, cy, c.k1, c.k2, c.p1, c.p2};
  return *find_model("OPENCV");
}

}  // namespace meshnbv::io::colmap
