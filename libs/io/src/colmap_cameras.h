// COLMAP 3.8 camera models <-> our camera (docs/conventions.md, docs/formats.md).
// Internal to meshnbv::io: shared by the text and binary model readers and
// the writer.
#pragma once

#include <string>
#include <vector>

#include "meshnbv/camera.h"

namespace meshnbv::io::colmap {

constexpr double kPixelOffset = 0.5;  // COLMAP pixel coordinate - ours

struct CameraModelSpec {
  int id;              // model_id in cameras.bin
  const char* name;    // MODEL in cameras.txt
  std::size_t num_params;
  const char* params;  // parameter names, in order
};

// Every model COLMAP 3.8 writes; nullptr when unknown.
const CameraModelSpec* find_model(const std::string& name);
const CameraModelSpec* find_model(int id);
// "SIMPLE_PINHOLE, PINHOLE, ..." for error messages.
std::string model_names();

// Intrinsics and lens in our convention (width/height unset). Throws Error
// (without file) for a model that does not map exactly: FOV with omega != 0,
// THIN_PRISM_FISHEYE with p1, p2, sx1 or sy1 non-zero.
PinholeCamera camera_from_params(const CameraModelSpec& model, const std::vector<double>& params);

// The model and parameters that hold `camera` exactly: PINHOLE, RADIAL
// (fx = fy, k1, k2), OPENCV (+ p1, p2), FULL_OPENCV (+ k3..k6) or
// OPENCV_FISHEYE. Throws Error for skew (COLMAP has none).
const CameraModelSpec& model_for(const PinholeCamera& camera, std::vector<double>* params);

}  // namespace meshnbv::io::colmap
