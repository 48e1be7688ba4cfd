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

  // The view's image comes from one of two sources; set at most one of them
  // (Scene::image and Scene::validate throw when both are set). With
  // neither, the view has no image: it is a candidate only (it can be
  // scored, it cannot contribute to PRI).
  //  - image_path: a file (absolute or working-directory-relative), decoded
  //    when needed through the scene's bounded ImageCache. The readers set
  //    it; the scene writers write it.
  //  - pixels: an image held in memory, shared and immutable, for hosts that
  //    already hold decoded pixels (VTK pipelines, MeshLab rasters). No file
  //    is involved: the host converts once and hands the image over
  //    (std::make_shared<const Image>(std::move(image))), the view keeps it
  //    alive (outside the cache's byte budget). A scene file cannot
  //    reference it: the writers throw (see image_file).
  std::string image_path;
  std::shared_ptr<const Image> pixels;
  // False marks a view the caller keeps aside as a candidate even though it
  // has an image (the paper's Middlebury experiment).
  bool used = true;

  bool has_image() const { return !image_path.empty() || pixels != nullptr; }
  bool image_in_memory() const { return pixels != nullptr; }
  // image_path, for writers that reference image files ("" when the view has
  // no image). Throws Error naming the view when its image is held in
  // memory: `purpose` says what needed a file (e.g. "a .mlp project").
  const std::string& image_file(const std::string& purpose) const;
};

struct Scene {
  TriangleMesh mesh;
  std::string mesh_path;  // where the mesh came from (may be empty)
  std::vector<View> views;
  std::string source;     // the path the scene was read from
  std::string format;     // "mlp", "json", "middlebury", "colmap", "bundler"
  std::vector<std::string> warnings;  // non-fatal remarks of the reader
  std::shared_ptr<ImageCache> images = std::make_shared<ImageCache>();

  // The image of view i: its in-memory pixels, else its file decoded via the
  // cache. Throws Error when the view has no image or both sources, the file
  // is missing or does not decode, or the image's size differs from the
  // camera's.
  std::shared_ptr<const Image> image(std::size_t view) const;
  std::size_t num_views_with_image() const;
  // Checks every camera (PinholeCamera::check), that no view has both image
  // sources, and the mesh (validate).
  void validate() const;
};

}  // namespace meshnbv
