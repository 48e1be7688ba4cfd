// Ray-casting renderer for synthetic scenes: procedural solid texture,
// view-independent shading (Lambert under a fixed directional light plus
// ambient), supersampling, optional z-depth output.
#pragma once

#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/image.h"
#include "meshnbv/progress.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/texture.h"

namespace meshnbv {

struct RenderOptions {
  int samples_per_pixel = 4;  // a stratified n x n grid uses the largest n with n^2 <= this
  Vec3 light_direction = Vec3(0.35, 0.25, 0.9);  // towards the light; normalised on use
  double ambient = 0.35;
  double diffuse = 0.65;
  Vec3 background = Vec3(0.62, 0.72, 0.85);  // sky colour
  bool textured_background = false;          // faint noise instead of a flat colour
};

struct RenderInputs {
  const TriangleMesh* mesh = nullptr;
  const RayCaster* raycaster = nullptr;  // built on *mesh
  const SolidTexture* texture = nullptr;
  // Per-face material ids (face attribute "material"); nullptr = all 0.
  const std::vector<float>* materials = nullptr;
  // Per-face colours used as albedo instead of the texture (quality maps);
  // then `texture` may be null.
  const std::vector<Rgb8>* face_colors = nullptr;
};

// Renders the RGB image seen by `camera`. When `depth` is given it receives
// W*H z-depths (camera frame) of the nearest surface at pixel centres,
// NaN where the ray misses. Rows run in parallel; the result does not
// depend on the number of threads.
Image render(const RenderInputs& inputs, const PinholeCamera& camera,
             const RenderOptions& options = {}, std::vector<float>* depth = nullptr,
             const ProgressCallback& progress = {});

}  // namespace meshnbv
