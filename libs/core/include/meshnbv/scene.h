// A scene: one mesh and a set of calibrated views (SPEC section 1).
#pragma once

#include <memory>
#include <string>
#include <utility>
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
  // How image_path's pixels are read (see ImageOrientation). The readers
  // leave `stored`, what the tools they read compute on; Scene::image turns
  // a photo by its EXIF tag by itself when only the turned photo has the
  // camera's size (the tool worked on the turned photo).
  ImageOrientation orientation = ImageOrientation::stored;
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

// A sparse 3-D point of the reconstruction (COLMAP points3D, OpenMVG
// structure) and where the tool measured it: view index and pixel, in our
// convention. Only for checking the import (reprojection_error).
struct SparsePoint {
  Vec3 position;
  std::vector<std::pair<int, Vec2>> observations;  // (view index, pixel)
};

// How well the sparse points reproject through the cameras, in pixels.
struct ReprojectionStats {
  std::size_t observations = 0;  // measured (point in front of the camera)
  std::size_t behind = 0;        // observations of a point behind its camera
  double median = 0, mean = 0, max = 0;
};

// The photo of a file-backed view decoded as Scene::image reads it (its
// orientation, the EXIF turn for a stored photo on its side, the size
// check), without a cache. Throws Error as Scene::image does.
std::shared_ptr<const Image> load_view_image(const View& view);

struct Scene {
  TriangleMesh mesh;
  std::string mesh_path;  // where the mesh came from (may be empty)
  std::vector<View> views;
  std::string source;     // the path the scene was read from
  std::string format;     // "mlp", "json", "middlebury", "colmap", "bundler"
  std::vector<std::string> warnings;  // non-fatal remarks of the reader
  // The tool that wrote the project as the reader recognised it, e.g.
  // "COLMAP (binary model)", "Agisoft Metashape (cameras XML)"; may be empty.
  std::string producer;
  std::vector<SparsePoint> sparse_points;  // when the file holds them
  // Where the source places the scene on Earth, else empty: the scene's
  // coordinates are in `crs` (anything PROJ reads: EPSG code, WKT), or, with
  // `crs_geocentric`, in the geocentric (ECEF) frame of that CRS's datum
  // (a georeferenced Metashape chunk's world frame).
  std::string crs;
  bool crs_geocentric = false;
  std::shared_ptr<ImageCache> images = std::make_shared<ImageCache>();

  // The image of view i: its in-memory pixels, else its file decoded via the
  // cache (in the view's orientation; a stored photo whose width and height
  // are the camera's swapped is read turned by its EXIF tag when that gives
  // the camera's size). Throws Error when the view has no image or both
  // sources, the file is missing or does not decode, or the image's size
  // differs from the camera's. `reduction` (1, 2, 4, 8): a JPEG file is
  // decoded that many times smaller (Image::load; the image's reduction()
  // says whether it was, and its size is then the camera's divided, rounded
  // up); in-memory pixels are always whole.
  std::shared_ptr<const Image> image(std::size_t view, int reduction = 1) const;
  std::size_t num_views_with_image() const;
  // Checks every camera (PinholeCamera::check), that no view has both image
  // sources, and the mesh (validate).
  void validate() const;
};

// Reprojection error of scene.sparse_points through the views' cameras.
ReprojectionStats reprojection_error(const Scene& scene);

// How much of the mesh lies in the views, ignoring occlusion: of up to
// 20,000 faces (sampled evenly), those whose centroid projects inside at
// least one camera's image, in front of it.
struct MeshViewCoverage {
  std::size_t faces_checked = 0, faces_in_view = 0;
  double share() const { return faces_checked ? double(faces_in_view) / double(faces_checked) : 1.0; }
};
MeshViewCoverage mesh_view_coverage(const Scene& scene);
// A plain one-line warning when fewer than half of the faces lie in any
// view (the mesh is probably in another coordinate frame than the
// cameras); "" otherwise, or when there is no mesh or no view.
std::string mesh_frame_warning(const Scene& scene);

}  // namespace meshnbv
