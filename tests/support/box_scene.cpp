#include "box_scene.h"

#include <cstdio>
#include <filesystem>

#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/synth/generators.h"

namespace meshnbv::test {

Scene make_box_scene(const BoxSceneOptions& o) {
  Scene scene;
  scene.mesh = synth::make_box(o.min, o.max, o.edge_length, 1);
  synth::CameraSetOptions co;
  co.count = o.views;
  co.width = o.width;
  co.height = o.height;
  co.elevation_degrees = 30;
  const auto cams = synth::make_cameras(scene.mesh, co);
  for (std::size_t k = 0; k < cams.size(); ++k) {
    View view;
    char label[32];
    std::snprintf(label, sizeof(label), "view_%02zu", k);
    view.label = label;
    view.camera = cams[k];
    scene.views.push_back(view);
  }
  return scene;
}

Image render_box(const BoxSceneOptions& o, const PinholeCamera& camera) {
  const TriangleMesh mesh = synth::make_box(o.min, o.max, o.edge_length, 1);
  const RayCaster caster(mesh);
  // Bricks 10 cm long: texture at the scale of this 1 m box.
  std::vector<Material> materials = default_materials();
  for (auto& m : materials) m.scale *= 0.2;
  const SolidTexture texture(1, materials);
  return render({&mesh, &caster, &texture, mesh.face_attribute(synth::kMaterialAttribute)}, camera);
}

void write_box_project(const std::string& folder, const BoxSceneOptions& o) {
  namespace fs = std::filesystem;
  Scene scene = make_box_scene(o);
  fs::create_directories(fs::path(folder) / "images");
  const std::string mesh_file = (fs::path(folder) / "box.ply").string();
  scene.mesh.face_attributes.clear();
  io::write_ply(scene.mesh, mesh_file);
  for (auto& view : scene.views) {
    view.image_path = (fs::path(folder) / "images" / (view.label + ".png")).string();
    render_box(o, view.camera).save(view.image_path);
  }
  io::write_mlp(scene, (fs::path(folder) / "box.mlp").string(), mesh_file, true);
}

}  // namespace meshnbv::test
