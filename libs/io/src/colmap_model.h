// A COLMAP model as read from its text or binary files, before it becomes a
// Scene. Internal to meshnbv::io.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/camera.h"

namespace meshnbv::io::colmap {

struct Camera {
  PinholeCamera intrinsics;  // our convention; R, t unset
  std::string model;         // COLMAP's model name
  long line = -1;            // text: its line; binary: -1
};

struct Image {
  long long id = 0;
  long long camera_id = 0;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  std::string name;
  long line = -1;
  std::vector<Vec2> points2d;  // COLMAP pixel coordinates (top-left pixel centre at 0.5, 0.5)
};

struct Point {
  Vec3 position = Vec3::Zero();
  std::vector<std::pair<long long, long long>> track;  // (IMAGE_ID, POINT2D_IDX)
};

struct Model {
  std::map<long long, Camera> cameras;
  std::vector<Image> images;  // sorted by id
  std::vector<Point> points;
  bool has_points = false;    // points3D.{txt,bin} was present
  std::string cameras_file, images_file, points_file;
};

// Binary model (cameras.bin, images.bin, points3D.bin if present) in `folder`.
// Every count is checked against the bytes left before anything is allocated.
Model read_binary_model(const std::string& folder);

}  // namespace meshnbv::io::colmap
