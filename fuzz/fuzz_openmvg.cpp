// OpenMVG sfm_data.json. Input: the file (root_path "images" and the like
// resolve against the working folder; the fixture images are found by name
// under scratch/images).
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(openmvg) {
  const std::string path = meshnbv::fuzz::write_input("openmvg/sfm_data.json", data, size);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::OpenMvg,
                                   meshnbv::fuzz::scratch() + "/images");
}
