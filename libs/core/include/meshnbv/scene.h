// A scene: one mesh and a set of calibrated views (SPEC section 1).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/image.h"
#include "meshnbv/mesh.h"

namespace meshnbv {

struct View {
  std::string label;
  PinholeCamera camera;
  // Absolute or working-directory-relative path; empty = no image: the view
  // is a candidate only (it can be scored, it cannot contribute to PRI).
  std::string image_path;
  // False marks a view the caller keeps aside as a candidate even though it
  // has an image (the paper's Middlebury experiment).
  bool used = true;

  bool has_image() const { return !image_path.empty(); }
};

struct Scene {
  TriangleMesh mesh;
  std::string mesh_path;  // where the mesh came from (may be empty)
  std::vector<View> views;
  std::string source;     // the path the scene was read from
  std::string format;     // "mlp", "json", "middlebury", "colmap", "bundler"
  std::vector<std::string> warnings;  // non-fatal remarks of the reader
  std::shared_ptr<ImageCache> images = std::make_shared<ImageCache>();

  // Decoded image of view i via the cache; throws Error when the view has
  // no image, the file is missing or does not decode, or its size differs
  // from the camera's.
  std::shared_ptr<const Image> image(std::size_t view) const;
  std::size_t num_views_with_image() const;
  // Checks every camera (PinholeCamera::check) and the mesh (validate).
  void validate() const;
};

}  // namespace meshnbv
