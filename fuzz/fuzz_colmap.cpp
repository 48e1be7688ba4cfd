// COLMAP text model. Input: cameras.txt, a line "%%%%", images.txt. The
// model folder is scratch/colmap/sparse, so <model>/../../images.. finds the
// fixture images (images/a.png, ...).
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(colmap) {
  std::string cameras, images;
  meshnbv::fuzz::split_two(data, size, &cameras, &images);
  meshnbv::fuzz::write_text("colmap/sparse/cameras.txt", cameras);
  meshnbv::fuzz::write_text("colmap/sparse/images.txt", images);
  return meshnbv::fuzz::fuzz_scene(meshnbv::fuzz::scratch() + "/colmap/sparse",
                                   meshnbv::io::SceneFormat::Colmap);
}
