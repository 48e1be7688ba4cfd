// The COLMAP backend's text files, and one tiny end-to-end loop (skipped
// with a message when the colmap executable is missing).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "meshnbv/error.h"
#include "meshnbv/eval/loop.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/synth/project.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace meshnbv::eval {
namespace {

TEST(EvalColmap, KnownPoseModelUsesColmapsPixelConvention) {
  View v;
  v.label = "a";
  v.camera = PinholeCamera::look_at(Vec3(3, 0, 1), Vec3::Zero(), Vec3(0, 0, 1), 500, 510, 319.5,
                                    239.5, 640, 480);
  const std::string dir = test::temp_dir("eval_known_model");
  write_known_pose_model({v}, {7}, {3}, {"a.png"}, dir);
  const std::string cams = io::read_file(dir + "/cameras.txt");
  EXPECT_NE(cams.find("3 PINHOLE 640 480 500 510 320 240"), std::string::npos) << cams;
  std::ifstream in(dir + "/images.txt");
  std::string line;
  std::getline(in, line);  // comment
  std::getline(in, line);
  std::istringstream ss(line);
  long long id, cam;
  double qw, qx, qy, qz, tx, ty, tz;
  std::string name;
  ss >> id >> qw >> qx >> qy >> qz >> tx >> ty >> tz >> cam >> name;
  EXPECT_EQ(id, 7);
  EXPECT_EQ(cam, 3);
  EXPECT_EQ(name, "a.png");
  EXPECT_GE(qw, 0.0);
  const Mat3 R = Eigen::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
  EXPECT_LT((R - v.camera.R).norm(), 1e-12);
  EXPECT_LT((Vec3(tx, ty, tz) - v.camera.t).norm(), 1e-12);
  std::getline(in, line);
  EXPECT_EQ(line, "");  // no 2-D points
  EXPECT_TRUE(fs::exists(dir + "/points3D.txt"));
}

TEST(EvalColmap, ReadsPointsAndTracks) {
  const std::string dir = test::temp_dir("eval_points3d");
  {
    std::ofstream f(dir + "/points3D.txt");
    f << "# POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
      << "1 0.5 -1 2 10 20 30 0.7 1 4 2 9 1 12\n"
      << "5 1 2 3 0 0 0 1.5 3 0 4 1\n";
  }
  const auto pts = read_colmap_points(dir + "/points3D.txt");
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[0].position, Vec3(0.5, -1, 2));
  EXPECT_DOUBLE_EQ(pts[0].error, 0.7);
  EXPECT_EQ(pts[0].image_ids, (std::vector<long long>{1, 2}));  // each image once
  EXPECT_EQ(pts[1].image_ids, (std::vector<long long>{3, 4}));
  {
    std::ofstream f(dir + "/bad.txt");
    f << "1 0 0 0 0 0 0 1 5\n";
  }
  MESHNBV_EXPECT_ERROR_CONTAINS(read_colmap_points(dir + "/bad.txt"), "TRACK");
}

TEST(EvalLoop, OptionsAreChecked) {
  LoopOptions o;
  o.out_dir = "x";
  o.bootstrap = 1;
  MESHNBV_EXPECT_ERROR_CONTAINS(o.check(), "at least 2 views");
  o.bootstrap = 3;
  o.max_views = 2;
  MESHNBV_EXPECT_ERROR_CONTAINS(o.check(), "below the bootstrap");
  o.max_views = 0;
  o.bootstrap_views = {0, 1};
  MESHNBV_EXPECT_ERROR_CONTAINS(o.check(), "2 bootstrap views given");
  o.bootstrap_views.clear();
  o.save_meshes = "some";
  MESHNBV_EXPECT_ERROR_CONTAINS(o.check(), "save meshes");
}

// A synthetic building, 12 ring views of 640 x 480 (30 degrees apart: SIFT
// still matches neighbours), bootstrap 3, two more
// views chosen by the next-best-view energy: every step is reconstructed
// by COLMAP + the mesher and measured against the truth.
TEST(EvalLoop, TinySyntheticLoopEndToEnd) {
  if (!colmap_available()) GTEST_SKIP() << "colmap not installed (apt-get install colmap): loop not run";
  const std::string dir = test::temp_dir("eval_loop");
  synth::SynthOptions so;
  so.scene = "building";
  so.cameras.count = 12;
  so.cameras.width = 640;
  so.cameras.height = 480;
  so.render.samples_per_pixel = 1;
  synth::write_synthetic_project(so, dir + "/synth");
  const Dataset d = load_dataset(dir + "/synth", dir + "/cache");
  ASSERT_TRUE(d.synthetic);
  ASSERT_EQ(d.views.size(), 12u);
  for (const View& v : d.views) EXPECT_TRUE(fs::exists(v.image_path));
  LoopOptions o;
  o.strategy = Strategy::Nbv;
  o.max_views = 5;
  o.out_dir = dir + "/out";
  o.cache_dir = dir + "/cache";
  std::vector<int> seen_steps;
  const LoopResult r = run_loop(d, o, {}, [&](const StepRecord& s) { seen_steps.push_back(s.step); });
  ASSERT_EQ(r.steps.size(), 3u);
  EXPECT_EQ(seen_steps, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(r.synthetic);
  EXPECT_EQ(r.thresholds.size(), 3u);
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const StepRecord& s = r.steps[k];
    EXPECT_EQ(s.views.size(), 3 + k);
    EXPECT_GT(s.points, 50u) << "step " << k;
    EXPECT_GT(s.faces, 50u) << "step " << k;
    EXPECT_TRUE(fs::exists(o.out_dir + "/" + s.mesh_file));
    if (k > 0) {
      EXPECT_FALSE(s.added.empty());
      EXPECT_EQ(s.views.back(), s.added);
      // Its pose, recorded (loop.json's added_camera): the dataset view's.
      ASSERT_TRUE(s.has_added_camera);
      const auto it =
          std::find_if(d.views.begin(), d.views.end(), [&](const View& v) { return v.label == s.added; });
      ASSERT_NE(it, d.views.end());
      EXPECT_LT((s.added_camera.center() - it->camera.center()).norm(), 1e-9);
    } else {
      EXPECT_FALSE(s.has_added_camera);
    }
    // Sparse but right: most of the reconstruction within 2% of the diagonal.
    EXPECT_LT(s.metrics.accuracy[0].second, r.thresholds[2]) << "step " << k;
  }
  // More views, not less of the truth (a little slack for the graph cut).
  EXPECT_GE(r.steps.back().metrics.completeness[2].second,
            r.steps.front().metrics.completeness[2].second - 0.02);
  EXPECT_TRUE(fs::exists(o.out_dir + "/steps.csv"));
  EXPECT_TRUE(fs::exists(o.out_dir + "/loop.json"));
  {
    std::ifstream f(o.out_dir + "/loop.json");
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"added_camera\""), std::string::npos);
  }
  EXPECT_TRUE(fs::exists(o.out_dir + "/reference.ply"));
  // The features and matches are cached: a second workspace reuses them.
  const ColmapWorkspace again(o.cache_dir + "/colmap", d.views);
  EXPECT_TRUE(again.reused_cache());
}

}  // namespace
}  // namespace meshnbv::eval
