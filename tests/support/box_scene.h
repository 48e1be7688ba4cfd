// A small scene with exactly known geometry for tests and the bundled sample
// project: an axis-aligned box (subdivided into a regular triangle grid per
// side), cameras on a ring around it, and images ray-cast analytically with
// a deterministic solid texture and Lambertian shading. (The Embree renderer
// with procedural scenes is a separate, later part of the core.)
#pragma once

#include <string>

#include "meshnbv/scene.h"

namespace meshnbv::test {

struct BoxSceneOptions {
  Vec3 min = Vec3(-0.5, -0.4, 0.0);
  Vec3 max = Vec3(0.5, 0.4, 0.6);
  int subdivisions = 4;  // grid cells per box side edge
  int views = 8;
  int width = 320, height = 240;
  double ring_radius = 2.5, ring_height = 1.2;
};

// Mesh and cameras (no images yet: image_path empty).
Scene make_box_scene(const BoxSceneOptions& options = {});
// Ray-casts the box into an RGB image seen by `camera`.
Image render_box(const BoxSceneOptions& options, const PinholeCamera& camera);
// Writes <folder>/box.ply, <folder>/images/view_XX.png and <folder>/box.mlp.
void write_box_project(const std::string& folder, const BoxSceneOptions& options = {});

}  // namespace meshnbv::test
