// A small scene with exactly known geometry for tests: an axis-aligned box
// (closed, triangulated on a grid), cameras on a ring around it, images
// rendered by the core renderer.
#pragma once

#include <string>

#include "meshnbv/scene.h"

namespace meshnbv::test {

struct BoxSceneOptions {
  Vec3 min = Vec3(-0.5, -0.4, 0.0);
  Vec3 max = Vec3(0.5, 0.4, 0.6);
  double edge_length = 0.25;
  int views = 8;
  int width = 320, height = 240;
};

// Mesh and cameras (no images yet: image_path empty).
Scene make_box_scene(const BoxSceneOptions& options = {});
// Renders the box as `camera` sees it.
Image render_box(const BoxSceneOptions& options, const PinholeCamera& camera);
// Writes <folder>/box.ply, <folder>/images/view_XX.png and <folder>/box.mlp.
void write_box_project(const std::string& folder, const BoxSceneOptions& options = {});

}  // namespace meshnbv::test
