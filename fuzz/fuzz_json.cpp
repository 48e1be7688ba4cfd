// Our JSON scene. The scratch folder holds mesh.ply/.obj/.off and image.png
// for the scene to refer to.
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(json) {
  const std::string path = meshnbv::fuzz::write_input("input.json", data, size);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::Json);
}
