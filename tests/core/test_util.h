// Helpers shared by the core tests.
#pragma once

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "meshnbv/camera.h"
#include "meshnbv/io/scene_io.h"

namespace meshnbv::test {

inline std::string data_dir() { return MESHNBV_TEST_DATA_DIR; }

// A camera at the origin looking along +z with focal length f (pixels) and
// the principal point at the centre of a width x height image.
inline PinholeCamera centred_camera(double f, int width, int height) {
  PinholeCamera c;
  c.fx = c.fy = f;
  c.cx = (width - 1) / 2.0;
  c.cy = (height - 1) / 2.0;
  c.width = width;
  c.height = height;
  return c;
}

// A fresh, empty folder for one test; per process, because ctest runs the
// tests of one executable as parallel processes.
inline std::string temp_dir(const std::string& name) {
  const char* root = std::getenv("MESHNBV_TMP");
  std::filesystem::path dir = std::filesystem::path(root ? root : "/tmp/meshnbv_tests") /
                              (name + "." + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline constexpr double kDeg = M_PI / 180.0;

// A double as text with every digit it has (17 significant), for files
// the tests write.
inline std::string num(double v) {
  std::ostringstream ss;
  ss.precision(17);
  ss << v;
  return ss.str();
}

// The scene (cameras only) through a JSON scene file and back.
inline Scene json_round_trip(const Scene& scene, const std::string& name) {
  const std::string path = temp_dir(name) + "/scene.json";
  Scene copy = scene;
  copy.mesh = {};
  io::write_json_scene(copy, path, "", true);
  return io::read_json_scene(path);
}

// The Middlebury templeRing folder, or empty when absent.
inline std::string temple_ring_dir() {
  const char* env = std::getenv("MESHNBV_SHARED_DATA");
  std::filesystem::path root = env ? env : MESHNBV_SHARED_DATA_DIR;
  std::filesystem::path dir = root / "middlebury" / "templeRing";
  if (std::filesystem::exists(dir / "templeR_par.txt")) return dir.string();
  return {};
}

}  // namespace meshnbv::test

#define MESHNBV_EXPECT_ERROR_CONTAINS(statement, fragment)                              \
  do {                                                                                  \
    try {                                                                               \
      statement;                                                                        \
      ADD_FAILURE() << "expected meshnbv::Error containing '" << (fragment) << "'";     \
    } catch (const meshnbv::Error& e_) {                                                \
      EXPECT_NE(std::string(e_.what()).find(fragment), std::string::npos)               \
          << "message was: " << e_.what();                                              \
    }                                                                                   \
  } while (0)
