// The visual report: pictures are real renderings with the quality map.
#include <filesystem>
#include <fstream>

#include "meshnbv/io/file_util.h"
#include "meshnbv/planner.h"
#include "meshnbv/options.h"
#include "meshnbv/report.h"
#include "meshnbv/results.h"
#include "meshnbv/synth/project.h"
#include "meshnbv/visualize.h"
#include "test_util.h"

using namespace meshnbv;
namespace fs = std::filesystem;

namespace {
std::size_t count_pixels(const Image& img, bool (*pred)(const std::uint8_t*)) {
  std::size_t n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) n += pred(img.pixel(x, y));
  return n;
}
bool is_red(const std::uint8_t* p) { return p[0] > 180 && p[1] < 90 && p[2] < 90; }
bool is_green(const std::uint8_t* p) { return p[1] > 120 && p[0] < 100 && p[2] < 100; }
bool is_magenta(const std::uint8_t* p) { return p[0] > 150 && p[2] > 150 && p[1] < 80; }
}  // namespace

TEST(Report, PicturesShowTheQualityMapAndTheSuggestions) {
  synth::SynthOptions o;
  o.scene = "building";
  o.cameras.count = 8;
  o.cameras.layout = synth::CameraLayout::Orbit;
  o.cameras.width = 320;
  o.cameras.height = 240;
  o.overwrite = true;
  const auto p = synth::write_synthetic_project(o, test::temp_dir("report_project"));
  const PriResult pri = compute_pri(p.scene);
  SuggestOptions so;
  so.top = 2;
  const SuggestResult sug = suggest_views(p.scene, pri.pri, so);
  ReportInputs in;
  in.scene = &p.scene;
  in.pri = &pri;
  in.suggestions = &sug;
  in.suggest_options = so;
  in.scene_path = "synthetic building";
  in.image_width = 480;
  in.image_height = 360;
  const std::string dir = test::temp_dir("report");
  const ReportFiles files = write_report(in, dir);
  ASSERT_TRUE(fs::exists(files.html));
  for (const char* f : {"overview_1.png", "overview_2.png", "cameras.png", "histogram.png", "nbv_1.png",
                        "nbv_2.png", "viewer/meshnbv_viewer.js", "viewer/report_data.js"})
    ASSERT_TRUE(fs::exists(fs::path(dir) / f)) << f;
  const Image overview = Image::load(dir + "/overview_1.png");
  // The overviews frame the mesh alone: it fills much of the picture
  // (white background); the picture of the whole rig shows it smaller.
  const double cover = coverage(overview, Vec3(1, 1, 1));
  EXPECT_GT(cover, 0.25) << "share of non-background pixels";
  EXPECT_LT(coverage(Image::load(dir + "/cameras.png"), Vec3(1, 1, 1)), cover);
  // Mostly green (good faces) with red where the worst faces are.
  EXPECT_GT(count_pixels(overview, is_green), 2000u);
  EXPECT_GT(count_pixels(overview, is_red), 50u);
  // The suggested camera sees the worst faces, highlighted in magenta.
  EXPECT_GT(count_pixels(Image::load(dir + "/nbv_1.png"), is_magenta), 20u);
  // The page embeds its pictures and lists the suggestions.
  const std::string html = io::read_file(files.html);
  EXPECT_NE(html.find("data:image/png;base64,iVBORw0KGgo"), std::string::npos);
  EXPECT_NE(html.find("<td class=l>nbv_2</td>"), std::string::npos);
  EXPECT_NE(html.find("Inputs, options and timings"), std::string::npos);
  // The 3-D view: its container and its two classic scripts, the data first.
  const std::size_t data_at = html.find("<script src=\"viewer/report_data.js\"></script>");
  ASSERT_NE(data_at, std::string::npos);
  EXPECT_GT(html.find("<script src=\"viewer/meshnbv_viewer.js\"></script>"), data_at);
  EXPECT_NE(html.find("<div id=\"meshnbv-viewer\">"), std::string::npos);
  EXPECT_NE(html.find("Display mesh: the " + std::to_string(p.scene.mesh.num_faces()) + " faces"), std::string::npos);
  const std::string data = io::read_file(dir + "/viewer/report_data.js");
  EXPECT_EQ(data.find("// MeshNBV report data"), 0u);
  EXPECT_NE(data.find("window.MESHNBV_REPORT = {"), std::string::npos);
  EXPECT_NE(data.find("\"format\":\"meshnbv-report-view\""), std::string::npos);
  EXPECT_GT(fs::file_size(dir + "/viewer/meshnbv_viewer.js"), 100000u) << "the bundled three.js";
  // The report names the measure and its unit, and what PRI rests on.
  EXPECT_NE(html.find("PRI measure <b>ssd</b>, in squared intensity."), std::string::npos);
  const PriEvidence e = pri_evidence(pri);
  EXPECT_GT(e.observed, 1000u);
  EXPECT_NE(html.find("of " + std::to_string(e.observed) + " observed faces, " + std::to_string(e.two_views) +
                      " rest on 2 views only and " + std::to_string(e.low_texture) + " on low texture"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=l>comparisons (pri_pairs)</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=l>texture (pri_texture)</td>"), std::string::npos);
  // ... lists every option of both tables.
  for (const auto& spec : pri_option_table())
    EXPECT_NE(html.find("<td class=l>" + spec.name + "</td>"), std::string::npos) << spec.name;
  for (const auto& spec : suggest_option_table())
    EXPECT_NE(html.find("<td class=l>" + spec.name + "</td>"), std::string::npos) << spec.name;
}

TEST(Visualize, HistogramAndOverviewCamera) {
  std::vector<float> v = {0.1f, 0.2f, 0.2f, 0.9f, std::numeric_limits<float>::quiet_NaN()};
  const Image h = histogram_image(v, 4, 300, 200, "test");
  EXPECT_EQ(h.width(), 300);
  EXPECT_GT(1.0 - coverage(h, Vec3(1, 1, 1)), 0.5);  // mostly white page
  EXPECT_GT(coverage(h, Vec3(1, 1, 1)), 0.02);        // with bars
  const std::vector<Vec3> pts = {Vec3(-1, -1, 0), Vec3(1, 1, 2), Vec3(5, 0, 1)};
  const PinholeCamera c = overview_camera(pts, 30, 35, 400, 300);
  for (const Vec3& q : pts) {
    Vec2 px;
    ASSERT_TRUE(c.project(q, &px));
    EXPECT_TRUE(c.in_image(px));
  }
}
