// MeshLab projects. The scratch folder holds mesh.ply/.obj/.off and
// image.png for the project to refer to.
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(mlp) {
  const std::string path = meshnbv::fuzz::write_input("input.mlp", data, size);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::Mlp);
}
