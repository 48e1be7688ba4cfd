// AliceVision / Meshroom sfm.json / cameras.sfm. Input: the file; image
// paths of another machine are found by name under scratch/images.
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(alicevision) {
  const std::string path = meshnbv::fuzz::write_input("alicevision/cameras.sfm", data, size);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::AliceVision,
                                   meshnbv::fuzz::scratch() + "/images");
}
