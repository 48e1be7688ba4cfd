// Bundler v0.3. Input: bundle.out, a line "%%%%", list.txt. The list's
// paths are relative to the scratch folder (images/a.png, images/b.png,
// c.png, image.png exist; broken.png does not decode).
#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(bundler) {
  std::string bundle, list;
  meshnbv::fuzz::split_two(data, size, &bundle, &list);
  meshnbv::fuzz::write_text("list.txt", list);
  const std::string path = meshnbv::fuzz::write_text("bundle.out", bundle);
  return meshnbv::fuzz::fuzz_scene(path, meshnbv::io::SceneFormat::Bundler);
}
