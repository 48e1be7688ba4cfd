// A textured plane z = 0 (4 m x 4 m) under cameras looking at its centre,
// rendered to PNG files: the scene of the PRI evidence and offset tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/scene.h"
#include "meshnbv/synth/generators.h"
#include "meshnbv/texture.h"
#include "test_util.h"

namespace meshnbv::test {

// The material and the four eyes the plane tests share: a noise texture
// seen from about 5 m above, from four sides of the centre.
inline const Material kPlaneNoise = {Pattern::Noise, Vec3(0.7, 0.6, 0.5), Vec3(0.3, 0.3, 0.3), 0.5, 0.45};
inline const std::vector<Vec3> kPlaneEyes = {{0.5, -1.0, 5.0}, {-1.5, 0.5, 5.0}, {1.5, 1.0, 4.5}, {0.0, 2.0, 5.0}};

struct PlaneSceneOptions {
  double edge = 0.5;         // the generator's edge length (m)
  std::uint64_t texture_seed = 3;
  double texture_scale = 0.1;  // the texture's band limit (m)
  double scale = 1.0;          // image size 200x150 and focal length 180 px times this
  bool look_down = false;      // each camera looks straight down (+y up in its image), not at the centre
  std::string extension = ".png";  // the photos' format
};

// The views of the true plane from `eyes`, images under temp_dir(name).
inline Scene plane_scene(const std::string& name, const Material& material, const std::vector<Vec3>& eyes,
                         const PlaneSceneOptions& o = {}) {
  const std::string dir = temp_dir(name);
  const TriangleMesh truth = synth::make_ground(Vec3(-2, -2, 0), Vec3(2, 2, 0), o.edge, 0);
  const RayCaster caster(truth);
  const SolidTexture texture(o.texture_seed, {material}, o.texture_scale);
  const int w = int(200 * o.scale), h = int(150 * o.scale);
  const double f = 180 * o.scale;
  Scene scene;
  scene.mesh = truth;
  scene.mesh.face_attributes.clear();
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    View v;
    v.label = "v" + std::to_string(i);
    const Vec3 target = o.look_down ? Vec3(eyes[i].x(), eyes[i].y(), 0) : Vec3(0, 0, 0);
    const Vec3 up = o.look_down ? Vec3(0, 1, 0) : Vec3(0, 1, 0.3);
    v.camera = PinholeCamera::look_at(eyes[i], target, up, f, f, 0.5 * w - 0.5, 0.5 * h - 0.5, w, h);
    v.image_path = dir + "/" + v.label + o.extension;
    render({&truth, &caster, &texture, truth.face_attribute(synth::kMaterialAttribute)}, v.camera)
        .save(v.image_path);
    scene.views.push_back(v);
  }
  return scene;
}

}  // namespace meshnbv::test
