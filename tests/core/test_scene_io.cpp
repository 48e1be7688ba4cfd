// Scene-level I/O: JSON round trip, format detection, conversions.
#include <filesystem>
#include <fstream>

#include "box_scene.h"
#include "meshnbv/error.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "test_util.h"

using namespace meshnbv;
namespace fs = std::filesystem;

namespace {
void expect_same_cameras(const Scene& a, const Scene& b, double tol) {
  ASSERT_EQ(a.views.size(), b.views.size());
  for (std::size_t i = 0; i < a.views.size(); ++i) {
    const PinholeCamera &p = a.views[i].camera, &q = b.views[i].camera;
    EXPECT_NEAR((p.R - q.R).norm(), 0, tol) << i;
    EXPECT_NEAR((p.t - q.t).norm(), 0, tol) << i;
    EXPECT_NEAR(p.fx, q.fx, tol * p.fx) << i;
    EXPECT_NEAR(p.fy, q.fy, tol * p.fy) << i;
    EXPECT_NEAR(p.cx, q.cx, tol * p.fx) << i;
    EXPECT_NEAR(p.cy, q.cy, tol * p.fy) << i;
    EXPECT_NEAR(p.k1, q.k1, tol) << i;
    EXPECT_EQ(p.width, q.width);
    EXPECT_EQ(p.height, q.height);
  }
}
}  // namespace

TEST(JsonScene, RoundTrip) {
  const std::string dir = test::temp_dir("json_roundtrip");
  Scene scene = test::make_box_scene();
  scene.views[2].camera.k1 = -0.05;  // JSON keeps distortion
  scene.views[3].used = false;
  scene.views[0].image_path = dir + "/images/a.png";
  scene.views[0].orientation = ImageOrientation::exif;
  io::write_scene(scene, dir + "/s.json");
  const Scene back = io::read_json_scene(dir + "/s.json");
  expect_same_cameras(scene, back, 1e-12);
  EXPECT_FALSE(back.views[3].used);
  EXPECT_EQ(back.views[0].orientation, ImageOrientation::exif);
  EXPECT_EQ(back.views[1].orientation, ImageOrientation::stored);
  EXPECT_TRUE(back.views[0].has_image());
  EXPECT_FALSE(back.views[1].has_image());
  EXPECT_EQ(back.mesh.num_faces(), scene.mesh.num_faces());
  EXPECT_EQ(fs::path(back.views[0].image_path).lexically_normal(),
            fs::path(dir + "/images/a.png").lexically_normal());
}

TEST(JsonScene, Errors) {
  const std::string dir = test::temp_dir("json_errors");
  std::ofstream(dir + "/bad.json") << "{ \"format\": \"meshnbv-scene\", ";
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_json_scene(dir + "/bad.json"), "malformed JSON");
  std::ofstream(dir + "/other.json") << "{\"a\": 1}";
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_json_scene(dir + "/other.json"), "not a MeshNBV scene");
  std::ofstream(dir + "/cam.json")
      << R"({"format":"meshnbv-scene","version":1,"views":[{"label":"x","camera":{"width":10,"height":10,"fx":0,"fy":5,"cx":5,"cy":5,"R":[[1,0,0],[0,1,0],[0,0,1]],"t":[0,0,0]}}]})";
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_json_scene(dir + "/cam.json"), "focal length");
  std::ofstream(dir + "/type.json")
      << R"({"format":"meshnbv-scene","version":1,"views":[{"camera":{"width":10,"height":10,"fx":"a","fy":5,"cx":5,"cy":5,"R":[[1,0,0],[0,1,0],[0,0,1]],"t":[0,0,0]}}]})";
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_json_scene(dir + "/type.json"), "\"fx\" must be a number");
  std::ofstream(dir + "/turn.json")
      << R"({"format":"meshnbv-scene","version":1,"views":[{"image_orientation":"rotated","camera":{"width":10,"height":10,"fx":5,"fy":5,"cx":5,"cy":5,"R":[[1,0,0],[0,1,0],[0,0,1]],"t":[0,0,0]}}]})";
  MESHNBV_EXPECT_ERROR_CONTAINS(
      io::read_json_scene(dir + "/turn.json"),
      "view 0: \"image_orientation\" must be \"stored\" or \"exif\", not \"rotated\"");
}

TEST(SceneIo, DetectsFormats) {
  const std::string dir = test::temp_dir("detect");
  fs::create_directories(dir + "/colmap");
  std::ofstream(dir + "/colmap/cameras.txt") << "";
  std::ofstream(dir + "/colmap/images.txt") << "";
  fs::create_directories(dir + "/mb");
  std::ofstream(dir + "/mb/temple_par.txt") << "0\n";
  fs::create_directories(dir + "/bundler");
  std::ofstream(dir + "/bundler/bundle.out") << "";
  std::ofstream(dir + "/a.mlp") << "";
  std::ofstream(dir + "/a.json") << "";
  fs::create_directories(dir + "/empty");
  EXPECT_EQ(io::detect_scene_format(dir + "/colmap"), io::SceneFormat::Colmap);
  EXPECT_EQ(io::detect_scene_format(dir + "/mb"), io::SceneFormat::Middlebury);
  EXPECT_EQ(io::detect_scene_format(dir + "/mb/temple_par.txt"), io::SceneFormat::Middlebury);
  EXPECT_EQ(io::detect_scene_format(dir + "/bundler"), io::SceneFormat::Bundler);
  EXPECT_EQ(io::detect_scene_format(dir + "/bundler/bundle.out"), io::SceneFormat::Bundler);
  EXPECT_EQ(io::detect_scene_format(dir + "/a.mlp"), io::SceneFormat::Mlp);
  EXPECT_EQ(io::detect_scene_format(dir + "/a.json"), io::SceneFormat::Json);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::detect_scene_format(dir + "/empty"), "cannot tell");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::detect_scene_format(dir + "/none"), "scene not found");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::parse_scene_format("xyz"), "unknown scene format");
}

TEST(SceneIo, MlpToColmapToJsonKeepsCameras) {
  const std::string dir = test::temp_dir("convert_chain");
  test::BoxSceneOptions options;
  options.width = 40;
  options.height = 30;
  test::write_box_project(dir + "/box", options);
  const Scene mlp = io::read_scene(dir + "/box/box.mlp");
  io::write_scene(mlp, dir + "/colmap");
  const Scene colmap = io::read_scene(dir + "/colmap");
  expect_same_cameras(mlp, colmap, 1e-9);
  EXPECT_EQ(colmap.num_views_with_image(), mlp.views.size());
  EXPECT_TRUE(fs::exists(colmap.views[0].image_path)) << colmap.views[0].image_path;
  io::write_scene(colmap, dir + "/s.json");
  const Scene json = io::read_scene(dir + "/s.json");
  expect_same_cameras(mlp, json, 1e-9);
  EXPECT_EQ(json.mesh.num_faces(), mlp.mesh.num_faces());
  EXPECT_EQ(json.image(3)->width(), 40);
}

TEST(SceneIo, ImageSizeMismatchIsAnError) {
  const std::string dir = test::temp_dir("size_mismatch");
  test::BoxSceneOptions options;
  options.width = 40;
  options.height = 30;
  test::write_box_project(dir, options);
  Scene scene = io::read_scene(dir + "/box.mlp");
  scene.views[0].camera.width = 41;
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.image(0), "camera says 41x30");
}

TEST(SceneIo, MeshOverride) {
  const std::string dir = test::temp_dir("mesh_override");
  test::write_box_project(dir);
  TriangleMesh tri;
  tri.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.faces = {{0, 1, 2}};
  io::write_ply(tri, dir + "/tri.ply");
  io::SceneReadOptions ro;
  ro.mesh_path = dir + "/tri.ply";
  EXPECT_EQ(io::read_scene(dir + "/box.mlp", ro).mesh.num_faces(), 1u);
}
