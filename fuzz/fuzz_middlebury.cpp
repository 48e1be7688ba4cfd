// Middlebury *_par.txt. The scratch folder holds v0.png and v1.png (64x48)
// and image.png for the camera lines to name.
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(middlebury) {
  const std::string path = meshnbv::fuzz::write_input("input_par.txt", data, size);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::Middlebury);
}
