// The filters run by meshlabserver (the build's private prefix, under
// xvfb-run) on the fixture project (make_project.sh), compared with the
// `meshnbv` command line on the same project.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "meshlab_test_support.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

using namespace meshnbv;
using namespace meshnbv::meshlab_test;

namespace {

const View* find_view(const Scene& scene, const std::string& label) {
  for (const View& v : scene.views)
    if (v.label == label) return &v;
  return nullptr;
}

// Face flags of an ASCII PLY written by MeshLab with `-m ff sa`.
std::vector<int> ascii_face_flags(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> face_properties;
  std::string element;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream ss(line);
    std::string word;
    ss >> word;
    if (word == "element") {
      ss >> element;
      (element == "vertex" ? vertices : faces) = 0;
      std::size_t n;
      ss >> n;
      (element == "vertex" ? vertices : faces) = n;
    } else if (word == "property" && element == "face") {
      std::string type, name;
      ss >> type;
      if (type == "list") ss >> type >> type;
      ss >> name;
      face_properties.push_back(name);
    }
  }
  const auto flags_at = std::find(face_properties.begin(), face_properties.end(), "flags");
  if (flags_at == face_properties.end()) throw std::runtime_error("no face flags in " + path);
  for (std::size_t v = 0; v < vertices; ++v) std::getline(in, line);
  std::vector<int> flags;
  for (std::size_t f = 0; f < faces && std::getline(in, line); ++f) {
    std::istringstream ss(line);
    int n, index;
    ss >> n;
    for (int k = 0; k < n; ++k) ss >> index;
    std::vector<std::string> rest;
    std::string token;
    while (ss >> token) rest.push_back(token);
    flags.push_back(std::stoi(rest.at(std::size_t(flags_at - face_properties.begin()) - 1)));
  }
  return flags;
}

void expect_failure(const Process& r, const std::string& reason) {
  EXPECT_EQ(r.status, 255) << "meshlabserver must fail cleanly (255), not crash\n" << r.output;
  EXPECT_NE(r.output.find(reason), std::string::npos) << "reason not logged\n" << r.output;
}

// Runs Compute PRI (sample script) and `meshnbv pri` on `project` and
// compares face quality (NaN included) and colours. Returns the number of
// unobserved faces.
std::size_t expect_pri_equals_cli(const std::string& dir, const std::string& project) {
  const Process ml = meshlabserver("-p " + quote(dir + "/" + project) + " -s " + quote(script("compute_pri")) +
                                   " -o " + quote(dir + "/ml_pri.ply") + " -m fq fc");
  EXPECT_EQ(ml.status, 0) << ml.output;
  EXPECT_NE(ml.output.find("Compute PRI (ssd, squared intensity): 14188 faces"), std::string::npos)
      << ml.output;
  EXPECT_NE(ml.output.find("PRI percentiles: p0"), std::string::npos) << ml.output;
  const Process cli = meshnbv_cli("pri " + quote(dir + "/" + project) + " --out " +
                                  quote(dir + "/cli_pri.ply") + " --json " +
                                  quote(dir + "/cli_pri.json") + " --quiet");
  EXPECT_EQ(cli.status, 0) << cli.output;
  if (ml.status != 0 || cli.status != 0) return 0;
  // The log's evidence counts are the CLI summary's.
  std::ifstream summary(dir + "/cli_pri.json");
  const nlohmann::json evidence = nlohmann::json::parse(summary)["evidence"];
  const std::string counts =
      "PRI evidence: " + std::to_string(evidence["two_views"].get<int>()) + " of " +
      std::to_string(evidence["observed"].get<int>()) + " observed faces rest on 2 views; " +
      std::to_string(evidence["low_texture"].get<int>()) + " on low texture (below 0.01)";
  EXPECT_NE(ml.output.find(counts), std::string::npos) << counts << "\n" << ml.output;

  const TriangleMesh a = io::read_mesh(dir + "/ml_pri.ply");
  const TriangleMesh b = io::read_mesh(dir + "/cli_pri.ply");
  EXPECT_EQ(a.num_vertices(), b.num_vertices());
  const std::vector<float>* qa = a.face_attribute("quality");
  const std::vector<float>* qb = b.face_attribute("quality");
  if (!qa || !qb || a.num_faces() != b.num_faces()) {
    ADD_FAILURE() << "no face quality, or different face counts";
    return 0;
  }
  std::size_t nan = 0, nan_mismatch = 0, colour_mismatch = 0;
  double max_diff = 0;
  for (std::size_t f = 0; f < a.num_faces(); ++f) {
    if (std::isnan((*qa)[f]) || std::isnan((*qb)[f])) {
      nan_mismatch += std::isnan((*qa)[f]) != std::isnan((*qb)[f]);
      nan += std::isnan((*qb)[f]);
    } else {
      max_diff = std::max(max_diff, double(std::abs((*qa)[f] - (*qb)[f])));
    }
    colour_mismatch += a.face_colors.at(f) != b.face_colors.at(f);
  }
  std::cout << project << ": faces " << a.num_faces() << ", unobserved " << nan
            << ", max |PRI difference| " << max_diff << "\n";
  EXPECT_EQ(nan_mismatch, 0u);
  EXPECT_LE(max_diff, 1e-5);
  EXPECT_EQ(colour_mismatch, 0u);
  return nan;
}

}  // namespace

TEST(MeshlabServer, ComputePriEqualsCommandLine) {
  const std::string dir = project_copy("compute_pri");
  EXPECT_GT(expect_pri_equals_cli(dir, "ml.mlp"), 0u) << "the fixture should have unobserved faces";
}

// The layer's MLMatrix44 (CMeshO::Tr) moves the mesh as MeshLab draws it;
// the core's .mlp reader applies it too.
TEST(MeshlabServer, ComputePriAppliesTheLayerTransform) {
  const std::string dir = project_copy("compute_pri_transformed");
  expect_pri_equals_cli(dir, "transformed.mlp");
}

TEST(MeshlabServer, SuggestNextViewEqualsCommandLine) {
  const std::string dir = project_copy("suggest");
  const std::string sug = edited_script("suggest_next_view", dir + "/suggest.mlx",
                                        {{"top", "2"}, {"add_frustum_layer", "true"}});
  // Compute PRI first: Suggest Next View then takes PRI from the face quality.
  const Process ml = meshlabserver("-p " + quote(dir + "/ml.mlp") + " -s " + quote(script("compute_pri")) +
                               " -s " + quote(sug) + " -w " + quote(dir + "/ml_out.mlp") +
                               " -o " + quote(dir + "/ml_frustums.ply") + " -l x -m fc fq");
  ASSERT_EQ(ml.status, 0) << ml.output;
  EXPECT_NE(ml.output.find("PRI = the mesh's face quality"), std::string::npos) << ml.output;
  EXPECT_NE(ml.output.find("nbv_1: energy "), std::string::npos) << ml.output;
  const Process cli = meshnbv_cli("suggest " + quote(dir + "/ml.mlp") + " --out " + quote(dir + "/cli.json") +
                          " --top 2 --mlp " + quote(dir + "/cli.mlp") + " --frustums " +
                          quote(dir + "/cli_frustums.ply") + " --quiet");
  ASSERT_EQ(cli.status, 0) << cli.output;

  const Scene ours = io::read_scene(dir + "/ml_out.mlp");
  const Scene theirs = io::read_scene(dir + "/cli.mlp");
  const double diag = theirs.mesh.bounding_box().diagonal();
  for (const char* label : {"nbv_1", "nbv_2"}) {
    SCOPED_TRACE(label);
    const View* a = find_view(ours, label);
    const View* b = find_view(theirs, label);
    ASSERT_TRUE(a && b);
    EXPECT_FALSE(a->has_image());
    const double centre = (a->camera.center() - b->camera.center()).norm();
    const double rotation = (a->camera.R - b->camera.R).cwiseAbs().maxCoeff();
    std::cout << label << ": centre difference " << centre << " (" << centre / diag
              << " of the scene diagonal), max rotation difference " << rotation << "\n";
    EXPECT_LE(centre, 1e-5 * diag);
    EXPECT_LE(rotation, 1e-5);
    EXPECT_EQ(a->camera.width, b->camera.width);
    EXPECT_EQ(a->camera.height, b->camera.height);
    EXPECT_NEAR(a->camera.fx, b->camera.fx, 1e-5 * b->camera.fx);
    EXPECT_NEAR(a->camera.fy, b->camera.fy, 1e-5 * b->camera.fy);
    EXPECT_NEAR(a->camera.cx, b->camera.cx, 1e-4);
    EXPECT_NEAR(a->camera.cy, b->camera.cy, 1e-4);
  }
  EXPECT_EQ(find_view(ours, "nbv_3"), nullptr);

  // The frustum layer (the last layer: -l x), face quality = rank.
  const TriangleMesh fa = io::read_mesh(dir + "/ml_frustums.ply");
  const TriangleMesh fb = io::read_mesh(dir + "/cli_frustums.ply");
  ASSERT_EQ(fa.num_faces(), fb.num_faces());
  ASSERT_EQ(fa.num_vertices(), fb.num_vertices());
  EXPECT_EQ(fa.num_faces(), 12u);
  double max_vertex = 0;
  for (std::size_t v = 0; v < fa.num_vertices(); ++v)
    max_vertex = std::max(max_vertex, (fa.vertices[v] - fb.vertices[v]).norm());
  EXPECT_LE(max_vertex, 1e-5 * diag);
  EXPECT_EQ(fa.faces, fb.faces);
  EXPECT_EQ(fa.face_colors, fb.face_colors);
  ASSERT_TRUE(fa.face_attribute("quality") && fb.face_attribute("rank"));
  EXPECT_EQ(*fa.face_attribute("quality"), *fb.face_attribute("rank"));
}

TEST(MeshlabServer, SuggestGivenCandidatesEqualsCommandLine) {
  // view_006 and view_007 have no image: they are the candidates, and PRI
  // is computed from the other six (the mesh has no face quality).
  const std::string dir = project_copy("suggest_given");
  const std::string sug = edited_script("suggest_next_view", dir + "/given.mlx", {{"candidates", "0"}});
  const Process ml = meshlabserver("-p " + quote(dir + "/given.mlp") + " -s " + quote(sug) + " -w " +
                               quote(dir + "/ml_out.mlp"));
  ASSERT_EQ(ml.status, 0) << ml.output;
  EXPECT_NE(ml.output.find("PRI computed with Compute PRI's defaults"), std::string::npos) << ml.output;
  const Process cli = meshnbv_cli("suggest " + quote(dir + "/given.mlp") + " --candidates given --out " +
                          quote(dir + "/cli.json") + " --quiet");
  ASSERT_EQ(cli.status, 0) << cli.output;
  std::ifstream in(dir + "/cli.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const std::string source = j.at("suggestions").at(0).at("source").get<std::string>();
  EXPECT_TRUE(source == "view_006" || source == "view_007") << source;
  EXPECT_NE(ml.output.find("[" + source + "]"), std::string::npos) << ml.output;

  const Scene ours = io::read_scene(dir + "/ml_out.mlp");
  const View* nbv = find_view(ours, "nbv_1");
  const View* candidate = find_view(ours, source);
  ASSERT_TRUE(nbv && candidate);
  EXPECT_LE((nbv->camera.center() - candidate->camera.center()).norm(),
            1e-5 * ours.mesh.bounding_box().diagonal());
  EXPECT_LE((nbv->camera.R - candidate->camera.R).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(MeshlabServer, SelectWorstFacesSelectsTheCommandLinesWorstFaces) {
  const std::string dir = project_copy("select");
  const Process cli = meshnbv_cli("pri " + quote(dir + "/ml.mlp") + " --out " + quote(dir + "/cli_pri.ply") +
                          " --json " + quote(dir + "/cli_pri.json") + " --summary-worst 25 --quiet");
  ASSERT_EQ(cli.status, 0) << cli.output;
  // The CLI's PLY (face quality with NaN) opened as a mesh: MeshLab reads PRI back.
  const std::string sel = edited_script("select_worst_faces", dir + "/select.mlx", {{"worst_faces", "25"}});
  const Process ml = meshlabserver("-i " + quote(dir + "/cli_pri.ply") + " -s " + quote(sel) + " -o " +
                               quote(dir + "/selected.ply") + " -m ff sa");
  ASSERT_EQ(ml.status, 0) << ml.output;
  EXPECT_NE(ml.output.find("selected 25 of 14188 faces"), std::string::npos) << ml.output;

  const std::vector<int> flags = ascii_face_flags(dir + "/selected.ply");
  ASSERT_EQ(flags.size(), 14188u);
  std::set<int> selected;
  for (std::size_t f = 0; f < flags.size(); ++f)
    if (flags[f] & 0x20) selected.insert(int(f));  // vcg's SELECTED face flag
  std::ifstream in(dir + "/cli_pri.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  std::set<int> worst;
  for (const auto& w : j.at("worst_faces")) worst.insert(w.at("face").get<int>());
  EXPECT_EQ(worst.size(), 25u);
  EXPECT_EQ(selected, worst);
}

TEST(MeshlabServer, SelectWorstFacesFailsWithoutFaceQuality) {
  const std::string dir = project_copy("select_no_quality");
  expect_failure(meshlabserver("-p " + quote(dir + "/ml.mlp") + " -s " +
                               quote(script("select_worst_faces"))),
                 "Select Worst Faces failed: the mesh layer 'degraded_out.ply' has no face quality");
}

TEST(MeshlabServer, ProjectWithoutRastersFailsWithReason) {
  const std::string dir = project_copy("no_rasters");
  expect_failure(meshlabserver("-p " + quote(dir + "/no_rasters.mlp") + " -s " + quote(script("compute_pri"))),
                 "Compute PRI failed: the document has no raster layers");
  expect_failure(meshlabserver("-p " + quote(dir + "/no_rasters.mlp") + " -s " +
                               quote(script("suggest_next_view"))),
                 "Suggest Next View failed: the document has no raster layers");
}

TEST(MeshlabServer, RastersWithoutImagesFailWithReason) {
  const std::string dir = project_copy("no_images");
  expect_failure(meshlabserver("-p " + quote(dir + "/no_images.mlp") + " -s " + quote(script("compute_pri"))),
                 "Compute PRI failed: none of the 8 raster layers has an image");
  expect_failure(meshlabserver("-p " + quote(dir + "/no_images.mlp") + " -s " +
                               quote(script("suggest_next_view"))),
                 "Suggest Next View failed: none of the 8 raster layers has an image");
}
