// A view's image from a file (View::image_path, decoded through the scene's
// cache) or from memory (View::pixels, a shared immutable Image handed over
// by a host such as VTK or MeshLab): the same pixels give bitwise the same
// PRI and suggestions, no file is read or written for in-memory images, and
// scene writers refuse them with a one-line error instead of writing a
// scene that silently lost its images.
#include <cmath>
#include <cstring>
#include <filesystem>

#include "box_scene.h"
#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/io/suggestions_io.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"
#include "test_util.h"

using namespace meshnbv;
namespace fs = std::filesystem;

namespace {

// The box project with some geometric error, read back from its .mlp.
Scene box_project(const std::string& dir) {
  test::BoxSceneOptions options;
  options.views = 6;
  test::write_box_project(dir, options);
  Scene scene = io::read_scene(dir + "/box.mlp");
  for (Vec3& p : scene.mesh.vertices) p.z() += 0.01 * std::sin(9 * p.x()) * std::cos(7 * p.y());
  return scene;
}

// The same scene with every image decoded once and held in memory.
Scene in_memory(const Scene& files) {
  Scene memory = files;
  memory.images = std::make_shared<ImageCache>();  // its own cache, to count its loads
  for (View& v : memory.views) {
    v.pixels = std::make_shared<const Image>(Image::load(v.image_path));
    v.image_path.clear();
  }
  return memory;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

}  // namespace

TEST(InMemoryImages, PriIsBitwiseIdenticalToTheSameImagesFromFiles) {
  const std::string dir = test::temp_dir("in_memory_pri");
  const Scene files = box_project(dir);
  const Scene memory = in_memory(files);
  for (const View& v : memory.views) {
    EXPECT_TRUE(v.has_image());
    EXPECT_TRUE(v.image_in_memory());
  }
  EXPECT_EQ(memory.num_views_with_image(), files.views.size());

  PriOptions ssd, ncc_colour, lattice;
  ncc_colour.measure = Measure::NCC;
  ncc_colour.color = true;
  lattice.samples_per_side = 4;
  lattice.threads = 1;
  for (const PriOptions* o : {&ssd, &ncc_colour, &lattice}) {
    const PriResult a = compute_pri(files, *o);
    const PriResult b = compute_pri(memory, *o);
    ASSERT_GT(a.observed, 100u);
    EXPECT_TRUE(same_bits(a.pri, b.pri)) << "PRI differs between files and memory";
    EXPECT_EQ(a.pri_views, b.pri_views);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.views_used, b.views_used);
  }
  EXPECT_EQ(memory.images->loads(), 0u) << "an in-memory view was decoded from a file";

  // No file is needed at all (the same scene from files, with a fresh cache, now fails).
  fs::remove_all(fs::path(dir) / "images");
  EXPECT_TRUE(same_bits(compute_pri(memory).pri, compute_pri(files).pri));
  Scene files_uncached = files;
  files_uncached.images = std::make_shared<ImageCache>();
  MESHNBV_EXPECT_ERROR_CONTAINS(compute_pri(files_uncached), "image file not found");
}

TEST(InMemoryImages, MixedSourcesAndSuggestionsEqualFiles) {
  const std::string dir = test::temp_dir("in_memory_mixed");
  const Scene files = box_project(dir);
  Scene mixed = in_memory(files);
  for (std::size_t i = 0; i < mixed.views.size(); i += 2) {  // every other view from its file
    mixed.views[i].pixels.reset();
    mixed.views[i].image_path = files.views[i].image_path;
  }
  const PriResult a = compute_pri(files);
  EXPECT_TRUE(same_bits(a.pri, compute_pri(mixed).pri));

  // The planner counts in-memory views as existing views, as files.
  SuggestOptions o;
  o.top = 2;
  o.sampling.directions = 64;
  o.threads = 1;
  const SuggestResult s = suggest_views(files, a.pri, o);
  const SuggestResult t = suggest_views(in_memory(files), a.pri, o);
  ASSERT_EQ(s.suggestions.size(), t.suggestions.size());
  for (std::size_t i = 0; i < s.suggestions.size(); ++i) {
    EXPECT_EQ(s.suggestions[i].camera.center(), t.suggestions[i].camera.center()) << i;
    EXPECT_EQ(s.suggestions[i].energy.total, t.suggestions[i].energy.total) << i;
  }
}

TEST(InMemoryImages, SceneImageSharesThePixelsAndChecksTheirSize) {
  Scene scene = test::make_box_scene();
  const PinholeCamera& c = scene.views[0].camera;
  auto pixels = std::make_shared<const Image>(Image(c.width, c.height, 3));
  scene.views[0].pixels = pixels;
  EXPECT_EQ(scene.image(0).get(), pixels.get()) << "the view's image was copied";
  EXPECT_EQ(scene.images->size(), 0u);

  scene.views[1].pixels = std::make_shared<const Image>(Image(c.width - 1, c.height, 1));
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.image(1), "in-memory image is 319x240 but its camera says 320x240");
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.image(2), "has no image");

  // Both sources: ambiguous, refused where the image is taken and by validate().
  scene.views[0].image_path = "/somewhere/view_00.png";
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.image(0), "both an image file and an in-memory image");
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.validate(), "view 'view_00'");
  MESHNBV_EXPECT_ERROR_CONTAINS(scene.views[0].image_file("a test"), "held in memory");
}

TEST(InMemoryImages, SceneWritersRefuseThemAndWriteNothing) {
  const std::string dir = test::temp_dir("in_memory_writers");
  Scene scene = test::make_box_scene();
  scene.views[1].image_path = dir + "/on_disk.png";  // a file view writes as before
  const PinholeCamera& c = scene.views[2].camera;
  scene.views[2].pixels = std::make_shared<const Image>(Image(c.width, c.height, 1));
  const std::string label = "view '" + scene.views[2].label + "'";
  const std::string out = dir + "/out";
  fs::create_directories(out);

  const std::string reason = "its image is held in memory, not in a file";
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_scene(scene, out + "/s.mlp"), label + ": " + reason);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_scene(scene, out + "/s.mlp"), "a MeshLab project (.mlp)");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_scene(scene, out + "/s.json"), "a JSON scene");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_scene(scene, out + "/colmap"), "a COLMAP model");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_mlp(scene, out + "/m.mlp", "", false), reason);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_json_scene(scene, out + "/j.json", "", false), reason);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_colmap(scene, out + "/c", false), reason);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_suggestions_mlp(scene, SuggestResult{}, out + "/n.mlp", false),
                                reason);
  try {
    io::write_scene(scene, out + "/s.mlp");
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
  }
  EXPECT_EQ(files_in(out), 0u) << "a writer left a file (e.g. the mesh) behind";

  // Without the in-memory view everything writes, the file view by its path.
  scene.views.erase(scene.views.begin() + 2);
  io::write_scene(scene, out + "/s.mlp");
  io::write_scene(scene, out + "/j.json");
  const Scene back = io::read_scene(out + "/j.json");
  EXPECT_TRUE(back.views[1].has_image());
  EXPECT_FALSE(back.views[0].has_image());
}
