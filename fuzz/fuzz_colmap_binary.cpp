// COLMAP binary model. Input: cameras.bin, a line "%%%%", images.bin, a
// line "%%%%", points3D.bin (absent when there is no second separator).
// The model folder is scratch/colmap_bin/sparse, so <model>/../../images
// finds the fixture images (images/a.png, ...).
#include <filesystem>

#include "fuzz_scene_readers.h"

MESHNBV_FUZZ_TARGET(colmap_binary) {
  std::string cameras, rest, images, points;
  meshnbv::fuzz::split_two(data, size, &cameras, &rest);
  meshnbv::fuzz::split_two(reinterpret_cast<const std::uint8_t*>(rest.data()), rest.size(), &images,
                           &points);
  const std::string dir = meshnbv::fuzz::scratch() + "/colmap_bin/sparse";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  meshnbv::fuzz::write_text("colmap_bin/sparse/cameras.bin", cameras);
  meshnbv::fuzz::write_text("colmap_bin/sparse/images.bin", images);
  if (!points.empty()) meshnbv::fuzz::write_text("colmap_bin/sparse/points3D.bin", points);
  return meshnbv::fuzz::fuzz_scene(dir, meshnbv::io::SceneFormat::Colmap);
}
