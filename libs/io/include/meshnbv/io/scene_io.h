// Scene formats and their detection from a path.
#pragma once

#include <string>

#include "meshnbv/scene.h"

namespace meshnbv::io {

enum class SceneFormat { Auto, Mlp, Json, Middlebury, Colmap, Bundler, Metashape, OpenMvg, AliceVision };

// "auto", "mlp", "json", "middlebury", "colmap", "bundler", "metashape",
// "openmvg", "alicevision"; throws Error otherwise.
SceneFormat parse_scene_format(const std::string& name);
std::string scene_format_name(SceneFormat format);
// From the path: *.mlp, *.json, a folder (or file) with *_par.txt, a folder
// with cameras.txt + images.txt or cameras.bin + images.bin (COLMAP), bundle.out
// (or a folder holding it), *.xml (Metashape), *.sfm (AliceVision), and a
// *.json told apart by its keys (OpenMVG "sfm_data_version", AliceVision
// "viewId", else ours).
// Throws Error naming what was looked for when nothing matches.
SceneFormat detect_scene_format(const std::string& path);

struct SceneReadOptions {
  SceneFormat format = SceneFormat::Auto;
  // Mesh to attach to formats that carry none (Middlebury, COLMAP, Bundler),
  // or to replace the project's own.
  std::string mesh_path;
  // Folder of the images for formats that name them relatively (COLMAP,
  // Bundler), by label (Metashape) or by paths of another machine (OpenMVG,
  // AliceVision): searched recursively by file name there.
  std::string image_dir;
};

Scene read_scene(const std::string& path, const SceneReadOptions& options = {});

struct SceneWriteOptions {
  SceneFormat format = SceneFormat::Auto;  // Auto: from the output path
  bool overwrite = false;
};

// The format write_scene writes to `path`: `format` unless Auto, else
// from the name (*.mlp, *.json, no extension = a COLMAP folder). Throws
// Error for a name it cannot tell.
SceneFormat scene_output_format(const std::string& path, SceneFormat format = SceneFormat::Auto);

// .mlp and .json write the mesh beside them as <stem>_mesh.ply when the
// scene has one; a COLMAP folder gets cameras.txt, images.txt, points3D.txt
// (and meshed.ply). Middlebury and Bundler are read-only.
void write_scene(const Scene& scene, const std::string& path,
                 const SceneWriteOptions& options = {});

// Each format's own entry points.
Scene read_mlp(const std::string& path);
// Why a MeshLab project cannot hold the scene's cameras, "" when it can:
// VCG's lens model is not ours, so any lens or skew is refused
// (docs/conventions.md). write_mlp throws with this message.
std::string mlp_unsupported_reason(const Scene& scene);
void write_mlp(const Scene& scene, const std::string& path, const std::string& mesh_file,
               bool overwrite);
Scene read_json_scene(const std::string& path);
void write_json_scene(const Scene& scene, const std::string& path, const std::string& mesh_file,
                      bool overwrite);
// `path`: the *_par.txt file or the folder holding exactly one.
Scene read_middlebury(const std::string& path);
// `path`: the folder with cameras.txt and images.txt, or cameras.bin and
// images.bin (a binary model; it wins when both are present, as in COLMAP).
// points3D.{txt,bin}, when present, fills scene.sparse_points. Every camera
// model of COLMAP 3.8 that maps exactly is read (colmap_cameras.cpp); the
// others are an Error naming the model. Images are looked up
// in `image_dir`, else <path>/images, <path>/../images, <path>/../../images,
// else <path> itself; the first folder holding the first image wins.
Scene read_colmap(const std::string& path, const std::string& image_dir = {});
void write_colmap(const Scene& scene, const std::string& folder, bool overwrite);
// "MODEL WIDTH HEIGHT PARAMS..." of cameras.txt for `camera`: the COLMAP
// model that holds it exactly (PINHOLE, RADIAL, OPENCV, FULL_OPENCV,
// OPENCV_FISHEYE). Throws Error for skew, which COLMAP cannot hold.
std::string colmap_camera_text(const PinholeCamera& camera);
// `path`: bundle.out or its folder; the image list is list.txt beside it
// (or ../list.txt). Image sizes are read from the image files.
Scene read_bundler(const std::string& path, const std::string& image_dir = {});
// Agisoft Metashape "Export Cameras" XML (metashape.cpp: conventions). No
// image paths in the file: images are found by camera label under
// `image_dir` (default: the XML's folder), recursively. Unaligned cameras
// (no <transform>) are left out with a warning.
Scene read_metashape(const std::string& path, const std::string& image_dir = {});
// OpenMVG sfm_data.json (openmvg.cpp); structure -> scene.sparse_points.
Scene read_openmvg(const std::string& path, const std::string& image_dir = {});
// AliceVision / Meshroom sfm.json or cameras.sfm (alicevision.cpp).
Scene read_alicevision(const std::string& path, const std::string& image_dir = {});

}  // namespace meshnbv::io
