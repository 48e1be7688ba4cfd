// A complete synthetic project: ground truth, a degraded reconstruction with
// known per-face error, rendered images, and the project files.
#pragma once

#include <string>
#include <vector>

#include "meshnbv/progress.h"
#include "meshnbv/renderer.h"
#include "meshnbv/scene.h"
#include "meshnbv/synth/degrade.h"
#include "meshnbv/synth/generators.h"

namespace meshnbv::synth {

struct SynthOptions {
  std::string scene = "building";  // building | fortress | city | object
  std::string mesh_file;           // for "object": any mesh the core reads
  GeneratorOptions generator;
  CameraSetOptions cameras;
  // Empty: one noise region and one dent, at random places from the seed.
  std::vector<Degradation> degradations;
  RenderOptions render;
  std::uint64_t seed = 1;
  bool write_depth = false;  // also images/<label>_depth.tiff (32-bit float)
  bool overwrite = false;

  // Throws Error for inconsistent options (object without a mesh, ...) and
  // values out of range: views in [2, 1000], image sides in [16, 8192]
  // pixels, samples per pixel in [1, 64], edge length 0 (the scene's
  // default d) or in [d / 4, 100] metres (at most 16 times the default
  // face count), at most 64 degradations, each within its own range.
  void check() const;
};

struct SynthProject {
  TriangleMesh truth;            // with face attribute "material"
  Scene scene;                   // the degraded mesh + views (images when written)
  std::vector<float> gt_error;   // per face of scene.mesh, metres
  std::vector<Vec3> region_centers;
  double completeness_threshold = 0;  // suggested (1% of the diagonal), stated in the README
};

// Builds the meshes and cameras (no images).
SynthProject make_synthetic_project(const SynthOptions& options);

// Renders the truth into every view of `project`, in memory (View::pixels,
// no image path), with the texture and render settings that
// write_synthetic_project uses: the same images without files.
void render_synthetic_views(const SynthOptions& options, SynthProject* project);

// Writes into `folder`: truth.ply, degraded.ply (face attribute gt_error),
// gt_error.csv, images/view_NNN.png, project.mlp (degraded mesh + rasters),
// scene.json, README.md. Refuses a non-empty folder unless overwrite.
SynthProject write_synthetic_project(const SynthOptions& options, const std::string& folder,
                                     const ProgressCallback& progress = {});

}  // namespace meshnbv::synth
