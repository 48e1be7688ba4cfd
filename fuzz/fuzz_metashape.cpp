// Agisoft Metashape cameras XML. Input: the XML file; images are looked up
// by camera label under the scratch folder (image, a, b, c, v0, v1).
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(metashape) {
  const std::string path = meshnbv::fuzz::write_input("metashape/cameras.xml", data, size);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::Metashape,
                                   meshnbv::fuzz::scratch() + "/images");
}
