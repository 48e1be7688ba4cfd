// One body for the scene format targets: read through io::read_scene with
// the format given (as `meshnbv --format` does), exercise what was read.
#pragma once

#include "fuzz_target.h"
#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"

namespace meshnbv::fuzz {

inline int fuzz_scene(const std::string& path, io::SceneFormat format,
                      const std::string& image_dir = {}) {
  io::SceneReadOptions options;
  options.format = format;
  options.image_dir = image_dir;
  Scene scene;
  try {
    scene = io::read_scene(path, options);
  } catch (const Error&) {
    return 0;  // refused with a message: fine
  }
  exercise_scene(scene);
  return 0;
}

}  // namespace meshnbv::fuzz
