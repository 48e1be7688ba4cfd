// Camera importers (Middlebury, COLMAP, Bundler): each checked against its
// format's own projection formula written out here, independently of the
// importer. Our convention: x_cam = R X + t, +z forward, y down, pixel
// centres at integer coordinates.
#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/image.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/scene_io.h"
#include "meshnbv/scene.h"
#include "test_util.h"

using namespace meshnbv;
namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

void write_blank_png(const fs::path& path, int width, int height) {
  fs::create_directories(path.parent_path());
  Image(width, height, 3).save(path.string());
}

bool has_warning(const Scene& scene, const std::string& fragment) {
  for (const auto& w : scene.warnings)
    if (w.find(fragment) != std::string::npos) return true;
  return false;
}

std::string all_warnings(const Scene& scene) {
  std::string out;
  for (const auto& w : scene.warnings) out += w + "\n";
  return out;
}

Vec2 project_or_fail(const PinholeCamera& cam, const Vec3& X) {
  Vec2 px(NAN, NAN);
  EXPECT_TRUE(cam.project(X, &px)) << "point behind the camera: " << X.transpose();
  return px;
}

// ------------------------------------------------------------ Middlebury

const Vec3 kTempleMin(-0.023121, -0.038009, -0.091940);
const Vec3 kTempleMax(0.078626, 0.121636, -0.017395);

std::vector<Vec3> temple_box_corners() {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i)
    corners.emplace_back(i & 1 ? kTempleMax.x() : kTempleMin.x(),
                         i & 2 ? kTempleMax.y() : kTempleMin.y(),
                         i & 4 ? kTempleMax.z() : kTempleMin.z());
  return corners;
}

#define REQUIRE_TEMPLE_RING(dir)                                                \
  const std::string dir = test::temple_ring_dir();                              \
  if (dir.empty())                                                              \
  GTEST_SKIP() << "Middlebury templeRing not found at " MESHNBV_SHARED_DATA_DIR \
                  "/middlebury/templeRing; set MESHNBV_SHARED_DATA"

struct RingStats {
  double mean = 0, stddev = 0;
};

RingStats distance_stats(const std::vector<Vec3>& points, const Vec3& centre) {
  double sum = 0, sum2 = 0;
  for (const Vec3& p : points) {
    const double d = (p - centre).norm();
    sum += d;
    sum2 += d * d;
  }
  const double n = static_cast<double>(points.size());
  RingStats s;
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  return s;
}

struct RingFit {
  Vec3 centre, normal;
  double radius = 0, plane_rms = 0;
};

// Plane by SVD, then the algebraic circle fit (Kasa) in that plane:
// |p|^2 = 2 c.p + (r^2 - |c|^2) is linear in c and the constant.
RingFit fit_ring(const std::vector<Vec3>& points) {
  const Eigen::Index n = static_cast<Eigen::Index>(points.size());
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p / static_cast<double>(n);
  Eigen::MatrixXd A(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) A.row(i) = (points[i] - mean).transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Vec3 e1 = svd.matrixV().col(0), e2 = svd.matrixV().col(1);
  Eigen::MatrixXd B(n, 3);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec2 q((points[i] - mean).dot(e1), (points[i] - mean).dot(e2));
    B.row(i) << 2 * q.x(), 2 * q.y(), 1;
    b(i) = q.squaredNorm();
  }
  const Vec3 sol = B.colPivHouseholderQr().solve(b);
  RingFit fit;
  fit.normal = svd.matrixV().col(2);
  fit.centre = mean + sol(0) * e1 + sol(1) * e2;
  fit.radius = std::sqrt(sol(2) + sol(0) * sol(0) + sol(1) * sol(1));
  fit.plane_rms = svd.singularValues()(2) / std::sqrt(static_cast<double>(n));
  return fit;
}

// The par file read with plain streams: P = K [R | t] per image.
std::vector<std::pair<std::string, Eigen::Matrix<double, 3, 4>>> read_par_projections(
    const std::string& file) {
  std::ifstream in(file);
  int n = 0;
  in >> n;
  std::vector<std::pair<std::string, Eigen::Matrix<double, 3, 4>>> out;
  for (int i = 0; i < n; ++i) {
    std::string name;
    Mat3 K, R;
    Vec3 t;
    in >> name;
    for (int k = 0; k < 9; ++k) in >> K(k / 3, k % 3);
    for (int k = 0; k < 9; ++k) in >> R(k / 3, k % 3);
    in >> t.x() >> t.y() >> t.z();
    Eigen::Matrix<double, 3, 4> Rt;
    Rt << R, t;
    out.emplace_back(name, K * Rt);
  }
  return out;
}

// Bad par files: only parsing is exercised, so no image is needed.
Scene read_par_text(const std::string& test_name, const std::string& text) {
  const fs::path dir = test::temp_dir(test_name);
  write_text(dir / "bad_par.txt", text);
  return io::read_middlebury((dir / "bad_par.txt").string());
}

const char* kGoodParLine = "a.png 500 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 0 0 0 1 0 0 2\n";

}  // namespace

TEST(Middlebury, TempleRingBoxProjectsInsideEveryImage) {
  REQUIRE_TEMPLE_RING(dir);
  const Scene scene = io::read_middlebury(dir);
  ASSERT_EQ(scene.views.size(), 47u);
  EXPECT_EQ(scene.format, "middlebury");
  EXPECT_TRUE(scene.warnings.empty()) << all_warnings(scene);
  EXPECT_TRUE(scene.mesh.empty());
  EXPECT_EQ(scene.views.front().label, "templeR0001.png");
  for (const View& view : scene.views) {
    EXPECT_EQ(view.camera.width, 640);
    EXPECT_EQ(view.camera.height, 480);
    EXPECT_TRUE(fs::path(view.image_path).is_absolute());
    EXPECT_TRUE(fs::exists(view.image_path)) << view.image_path;
    for (const Vec3& corner : temple_box_corners()) {
      const Vec2 px = project_or_fail(view.camera, corner);
      EXPECT_TRUE(view.camera.in_image(px))
          << view.label << ": corner " << corner.transpose() << " -> " << px.transpose();
    }
  }
}

TEST(Middlebury, TempleRingCentresLieOnARing) {
  REQUIRE_TEMPLE_RING(dir);
  const Scene scene = io::read_middlebury(dir);
  std::vector<Vec3> centres;
  for (const View& view : scene.views) centres.push_back(view.camera.center());

  // Distance to the published box centre. The ring's axis misses the box
  // centre by about 8 mm, so this spread is about 1.0 % (measured 1.0116 %):
  // asserted with a 1.5 % bound.
  const Vec3 box_centre = 0.5 * (kTempleMin + kTempleMax);
  const RingStats to_box = distance_stats(centres, box_centre);
  std::cout << "[ templeRing ] distance to the box centre: mean " << to_box.mean << ", std "
            << to_box.stddev << ", std/mean " << to_box.stddev / to_box.mean << "\n";
  RecordProperty("box_centre_std_over_mean", std::to_string(to_box.stddev / to_box.mean));
  EXPECT_GT(to_box.mean, 0.3);  // the gantry ring is about half a metre away
  EXPECT_LT(to_box.mean, 1.0);
  EXPECT_LT(to_box.stddev / to_box.mean, 0.015);

  // The tight statement: a least-squares circle through the centres.
  const RingFit ring = fit_ring(centres);
  const RingStats to_ring = distance_stats(centres, ring.centre);
  std::cout << "[ templeRing ] fitted ring: radius " << ring.radius << ", plane RMS "
            << ring.plane_rms << ", std/mean of the distance to its centre "
            << to_ring.stddev / to_ring.mean << "\n";
  RecordProperty("ring_std_over_mean", std::to_string(to_ring.stddev / to_ring.mean));
  EXPECT_LT(ring.plane_rms, 1e-3 * ring.radius);
  EXPECT_LT(to_ring.stddev / to_ring.mean, 1e-3);
  // The ring surrounds the object: its axis passes within the box.
  const Vec3 off_axis =
      (box_centre - ring.centre) - (box_centre - ring.centre).dot(ring.normal) * ring.normal;
  EXPECT_LT(off_axis.norm(), 0.5 * (kTempleMax - kTempleMin).minCoeff());
}

TEST(Middlebury, TempleRingMatchesParProjection) {
  REQUIRE_TEMPLE_RING(dir);
  const Scene scene = io::read_middlebury(dir);
  const auto projections = read_par_projections(dir + "/templeR_par.txt");
  ASSERT_EQ(projections.size(), scene.views.size());
  std::vector<Vec3> points = temple_box_corners();
  points.push_back(0.5 * (kTempleMin + kTempleMax));
  for (std::size_t i = 0; i < scene.views.size(); i += 5) {
    EXPECT_EQ(scene.views[i].label, projections[i].first);
    for (const Vec3& X : points) {
      const Vec3 h = projections[i].second * X.homogeneous();
      const Vec2 expected(h.x() / h.z(), h.y() / h.z());
      const Vec2 px = project_or_fail(scene.views[i].camera, X);
      EXPECT_NEAR(px.x(), expected.x(), 1e-9);
      EXPECT_NEAR(px.y(), expected.y(), 1e-9);
    }
  }
}

TEST(Middlebury, MissingImageBecomesCandidateWithWarning) {
  const fs::path dir = test::temp_dir("middlebury_missing_image");
  fs::copy_file(test::data_dir() + "/middlebury/tiny/tiny_par.txt", dir / "tiny_par.txt");
  write_blank_png(dir / "v1.png", 64, 48);                // v0.png is missing
  const Scene scene = io::read_middlebury(dir.string());  // the folder form
  ASSERT_EQ(scene.views.size(), 2u);
  EXPECT_FALSE(scene.views[0].has_image());
  EXPECT_EQ(scene.views[1].image_path, (dir / "v1.png").string());
  EXPECT_TRUE(has_warning(scene, "1 of 2 images missing")) << all_warnings(scene);
  for (const View& v : scene.views) {
    EXPECT_EQ(v.camera.width, 64);
    EXPECT_EQ(v.camera.height, 48);
    EXPECT_EQ(v.camera.cx, 31.5);  // as given: no half-pixel shift
    EXPECT_EQ(v.camera.cy, 23.5);
    EXPECT_EQ(v.camera.fy, 510.0);
  }
  EXPECT_TRUE(
      scene.views[1].camera.R.isApprox((Mat3() << 0, 0, 1, 0, 1, 0, -1, 0, 0).finished(), 1e-15));
  EXPECT_EQ(scene.views[1].camera.t, Vec3(0, 0, 2.5));
}

TEST(Middlebury, NoImageAtAllIsAnError) {
  const fs::path dir = test::temp_dir("middlebury_no_image");
  fs::copy_file(test::data_dir() + "/middlebury/tiny/tiny_par.txt", dir / "tiny_par.txt");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_middlebury((dir / "tiny_par.txt").string()),
                                "none of the 2 images is present");
}

TEST(Middlebury, FolderWithSeveralParFilesIsAnError) {
  const fs::path dir = test::temp_dir("middlebury_two_par");
  write_text(dir / "a_par.txt", "1\n");
  write_text(dir / "b_par.txt", "1\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_middlebury(dir.string()), "a_par.txt, b_par.txt");
}

TEST(Middlebury, BadParLineWithTooFewNumbers) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      read_par_text("par_too_few", std::string("2\n") + kGoodParLine +
                                       "b.png 500 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 0 0\n"),
      "bad_par.txt:3: expected 22 fields (name + 21 numbers), got 17");
}

TEST(Middlebury, BadParNonNumber) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      read_par_text("par_non_number",
                    "1\na.png 500 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 zero 0 0 1 0 0 2\n"),
      ":2: expected a number for r23, got 'zero'");
}

TEST(Middlebury, BadParNaN) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      read_par_text("par_nan", "1\na.png 500 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 0 0 0 1 0 nan 2\n"),
      "t2 is not a finite number ('nan')");
}

TEST(Middlebury, BadParZeroFocalLength) {
  MESHNBV_EXPECT_ERROR_CONTAINS(
      read_par_text("par_zero_focal",
                    "1\na.png 0 0 31.5 0 510 23.5 0 0 1 1 0 0 0 1 0 0 0 1 0 0 2\n"),
      "zero focal length (k11 = 0)");
}

TEST(Middlebury, BadParCountMismatch) {
  MESHNBV_EXPECT_ERROR_CONTAINS(read_par_text("par_count", std::string("3\n") + kGoodParLine),
                                "declares 3 cameras but holds 1 camera lines");
}

// ------------------------------------------------------------ COLMAP

namespace {

// COLMAP's projection (pixel centre of the top-left pixel at (0.5, 0.5)):
// u = f x' d + cx, d = 1 + k1 r^2 + k2 r^4 on x' = x/z.
Vec2 colmap_project(const Mat3& R, const Vec3& t, double fx, double fy, double cx, double cy,
                    double k1, double k2, const Vec3& X) {
  const Vec3 c = R * X + t;
  const double x = c.x() / c.z(), y = c.y() / c.z(), r2 = x * x + y * y;
  const double d = 1 + k1 * r2 + k2 * r2 * r2;
  return {fx * x * d + cx, fy * y * d + cy};
}

void expect_relative(double actual, double expected, const char* what) {
  EXPECT_NEAR(actual, expected, 1e-9 * std::max(1.0, std::abs(expected))) << what;
}

void expect_close_camera(const PinholeCamera& a, const PinholeCamera& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  expect_relative(a.fx, b.fx, "fx");
  expect_relative(a.fy, b.fy, "fy");
  expect_relative(a.cx, b.cx, "cx");
  expect_relative(a.cy, b.cy, "cy");
  expect_relative(a.k1, b.k1, "k1");
  expect_relative(a.k2, b.k2, "k2");
  EXPECT_LT((a.R - b.R).norm(), 1e-9);
  EXPECT_LT((a.t - b.t).norm(), 1e-9 * std::max(1.0, b.t.norm()));
}

// A model folder with the given files, for the bad-input tests.
std::string colmap_model(const std::string& test_name, const std::string& cameras,
                         const std::string& images) {
  const fs::path dir = test::temp_dir(test_name);
  write_text(dir / "cameras.txt", cameras);
  write_text(dir / "images.txt", images);
  return dir.string();
}

// `c_folder`: where view 2's image lives.
Scene round_trip_scene(const fs::path& root, const fs::path& c_folder) {
  Scene scene;
  // view 0: fx != fy, no distortion -> PINHOLE; image under <root>/images.
  PinholeCamera pinhole = PinholeCamera::look_at({0.3, -2, 1.5}, {0, 0, 0}, {0, 0, 1}, 812.25,
                                                 790.5, 330.125, 241.75, 640, 480);
  // views 1 and 2 share one RADIAL camera; view 3 is OPENCV (fx != fy, k1).
  PinholeCamera radial = PinholeCamera::look_at({2, 0.1, 0.7}, {0.1, 0, 0}, {0, 0, 1}, 1234.5678,
                                                1234.5678, 399.5, 299.5, 800, 600);
  radial.k1 = -0.123456789;
  radial.k2 = 0.0345;
  PinholeCamera radial2 = radial;
  radial2.R = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  radial2.t = Vec3(0.01, -0.02, 3.5);
  PinholeCamera opencv = pinhole;
  opencv.k1 = 0.05;
  write_blank_png(root / "images" / "a.png", 640, 480);
  write_blank_png(root / "images" / "sub" / "b.png", 800, 600);
  write_blank_png(c_folder / "c.png", 800, 600);
  scene.views.push_back({"a", pinhole, (root / "images" / "a.png").string(), {}});
  scene.views.push_back({"b", radial, (root / "images" / "sub" / "b.png").string(), {}});
  scene.views.push_back({"c", radial2, (c_folder / "c.png").string(), {}});
  scene.views.push_back({"candidate_d", opencv, "", {}});
  scene.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  scene.mesh.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return scene;
}

}  // namespace

TEST(Colmap, HandWrittenModel) {
  const Scene scene = io::read_colmap(test::data_dir() + "/colmap/handwritten");
  EXPECT_EQ(scene.format, "colmap");
  ASSERT_EQ(scene.views.size(), 3u);
  // Sorted by IMAGE_ID: 5, 9, 12.
  EXPECT_EQ(scene.views[0].label, "identity.png");
  EXPECT_EQ(scene.views[1].label, "cyclic.png");
  EXPECT_EQ(scene.views[2].label, "rot_z90.png");
  // No image folder exists beside the model: paths fall back to the model folder.
  EXPECT_TRUE(has_warning(scene, "images not found")) << all_warnings(scene);
  EXPECT_EQ(fs::path(scene.views[2].image_path),
            fs::path(test::data_dir()) / "colmap" / "handwritten" / "rot_z90.png");
  EXPECT_TRUE(scene.mesh.empty());

  // Rotations written out by hand: R e_x, R e_y, R e_z are the columns.
  const Mat3 rot_z90 = (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
  const Mat3 cyclic = (Mat3() << 0, 0, 1, 1, 0, 0, 0, 1, 0).finished();  // x->y->z->x
  EXPECT_LT((scene.views[0].camera.R - Mat3::Identity()).norm(), 1e-15);
  EXPECT_LT((scene.views[1].camera.R - cyclic).norm(), 1e-15);
  EXPECT_LT((scene.views[2].camera.R - rot_z90).norm(), 1e-15);
  EXPECT_EQ(scene.views[0].camera.t, Vec3(0, 0, 5));
  EXPECT_EQ(scene.views[1].camera.t, Vec3(-0.3, 0.25, 6));
  EXPECT_EQ(scene.views[2].camera.t, Vec3(0.1, -0.2, 4));

  const PinholeCamera& simple = scene.views[2].camera;  // SIMPLE_PINHOLE 640 480 500 320 240
  EXPECT_EQ(simple.width, 640);
  EXPECT_EQ(simple.height, 480);
  EXPECT_EQ(simple.fx, 500.0);
  EXPECT_EQ(simple.fy, 500.0);
  EXPECT_EQ(simple.cx, 319.5);
  EXPECT_EQ(simple.cy, 239.5);
  EXPECT_FALSE(simple.has_distortion());
  const PinholeCamera& radial =
      scene.views[0].camera;  // SIMPLE_RADIAL 800 600 700 400.25 299.75 -0.08
  EXPECT_EQ(radial.fx, 700.0);
  EXPECT_EQ(radial.cx, 399.75);
  EXPECT_EQ(radial.cy, 299.25);
  EXPECT_EQ(radial.k1, -0.08);
  EXPECT_EQ(radial.k2, 0.0);
}

TEST(Colmap, ProjectionIsColmapsMinusHalfPixel) {
  const Scene scene = io::read_colmap(test::data_dir() + "/colmap/handwritten");
  ASSERT_EQ(scene.views.size(), 3u);
  const Mat3 rot_z90 = (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
  const Vec3 X(0.3, -0.1, 1.0);
  // Image 12: SIMPLE_PINHOLE f 500, c (320, 240); R X + t = (0.2, 0.1, 5).
  Vec2 expected = colmap_project(rot_z90, {0.1, -0.2, 4}, 500, 500, 320, 240, 0, 0, X);
  EXPECT_NEAR(expected.x(), 340.0, 1e-12);  // hand check of the formula itself
  Vec2 px = project_or_fail(scene.views[2].camera, X);
  EXPECT_NEAR(px.x(), expected.x() - 0.5, 1e-9);
  EXPECT_NEAR(px.y(), expected.y() - 0.5, 1e-9);
  // Image 5: SIMPLE_RADIAL, identity pose, t (0, 0, 5).
  for (const Vec3& Y : {Vec3(1, -0.5, 0), Vec3(-2, 1.5, 1), Vec3(0, 0, 0)}) {
    expected = colmap_project(Mat3::Identity(), {0, 0, 5}, 700, 700, 400.25, 299.75, -0.08, 0, Y);
    px = project_or_fail(scene.views[0].camera, Y);
    EXPECT_NEAR(px.x(), expected.x() - 0.5, 1e-9);
    EXPECT_NEAR(px.y(), expected.y() - 0.5, 1e-9);
  }
}

TEST(Colmap, RoundTripPinholeRadialOpencv) {
  const fs::path root = test::temp_dir("colmap_round_trip");
  const Scene scene = round_trip_scene(root, root / "images");
  const fs::path model = root / "sparse";
  io::write_colmap(scene, model.string(), false);

  // Views 1 and 2 share their intrinsics: 3 cameras for 4 views.
  const std::string cameras = io::read_file((model / "cameras.txt").string());
  EXPECT_NE(cameras.find("1 PINHOLE 640 480"), std::string::npos) << cameras;
  EXPECT_NE(cameras.find("2 RADIAL 800 600"), std::string::npos) << cameras;
  EXPECT_NE(cameras.find("3 OPENCV 640 480"), std::string::npos) << cameras;
  EXPECT_NE(cameras.find("# Number of cameras: 3"), std::string::npos) << cameras;
  EXPECT_TRUE(fs::exists(model / "points3D.txt"));
  EXPECT_TRUE(fs::exists(model / "meshed.ply"));

  const Scene back = io::read_colmap(model.string());
  EXPECT_TRUE(back.warnings.empty()) << all_warnings(back);
  ASSERT_EQ(back.views.size(), scene.views.size());
  for (std::size_t i = 0; i < scene.views.size(); ++i) {
    SCOPED_TRACE("view " + std::to_string(i));
    expect_close_camera(back.views[i].camera, scene.views[i].camera);
    if (scene.views[i].has_image()) {
      EXPECT_TRUE(fs::equivalent(back.views[i].image_path, scene.views[i].image_path));
    }
  }
  // Names relative to <model>/../images; the candidate keeps its label.
  EXPECT_EQ(back.views[0].label, "a.png");
  EXPECT_EQ(back.views[1].label, "sub/b.png");
  EXPECT_EQ(back.views[2].label, "c.png");
  EXPECT_EQ(back.views[3].label, "candidate_d");
  EXPECT_EQ(back.mesh.num_faces(), 4u);
  EXPECT_EQ(fs::path(back.mesh_path).filename(), "meshed.ply");
}

TEST(Colmap, WriteNamesImagesOutsideTheImageFolder) {
  // c.png is outside <model>/../images: names become relative to the model
  // folder, and still resolve to the same files when read back.
  const fs::path root = test::temp_dir("colmap_images_elsewhere");
  const Scene scene = round_trip_scene(root, root / "elsewhere");
  const fs::path model = root / "sparse";
  io::write_colmap(scene, model.string(), false);
  const Scene back = io::read_colmap(model.string());
  EXPECT_TRUE(back.warnings.empty()) << all_warnings(back);
  ASSERT_EQ(back.views.size(), scene.views.size());
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_TRUE(fs::equivalent(back.views[i].image_path, scene.views[i].image_path))
        << back.views[i].image_path;
  EXPECT_EQ(back.views[2].label, "../elsewhere/c.png");
}

TEST(Colmap, WriteRefusesToOverwrite) {
  const fs::path root = test::temp_dir("colmap_overwrite");
  Scene scene = round_trip_scene(root, root / "images");
  const fs::path model = root / "sparse";
  write_text(model / "points3D.txt", "keep me\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_colmap(scene, model.string(), false), "points3D.txt");
  // Checked before writing anything: no file appeared.
  EXPECT_FALSE(fs::exists(model / "cameras.txt"));
  EXPECT_EQ(io::read_file((model / "points3D.txt").string()), "keep me\n");
  io::write_colmap(scene, model.string(), true);
  EXPECT_TRUE(fs::exists(model / "cameras.txt"));
}

TEST(Colmap, UnknownModelIsAnError) {
  const std::string dir =
      colmap_model("colmap_unknown_model", "1 FISHEYE 640 480 500 500 320 240 0 0 0 0\n",
                   "1 1 0 0 0 0 0 5 1 a.png\n\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir),
                                "cameras.txt:1: unknown camera model 'FISHEYE' (COLMAP 3.8 models: "
                                "SIMPLE_PINHOLE, PINHOLE");
}

TEST(Colmap, ModelWithoutExactEquivalentIsAnErrorNamingIt) {
  std::string dir = colmap_model("colmap_fov", "1 FOV 640 480 500 500 320 240 0.9\n",
                                 "1 1 0 0 0 0 0 5 1 a.png\n\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir), "cameras.txt:1: camera model FOV (omega = 0.9");
  dir = colmap_model("colmap_prism",
                     "1 THIN_PRISM_FISHEYE 640 480 500 500 320 240 0.01 0 0.001 0 0 0 0 0\n",
                     "1 1 0 0 0 0 0 5 1 a.png\n\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir),
                                "camera model THIN_PRISM_FISHEYE with p1, p2, sx1 or sy1 non-zero");
}

TEST(Colmap, ImageWithUnknownCameraIdIsAnError) {
  const std::string dir =
      colmap_model("colmap_unknown_camera", "1 PINHOLE 640 480 500 500 320 240\n",
                   "# comment\n1 1 0 0 0 0 0 5 1 a.png\n\n"
                   "2 1 0 0 0 0 0 5 4 b.png\n\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir),
                                "images.txt:4: image 2 ('b.png') refers to camera 4");
}

TEST(Colmap, NaNParameterIsAnError) {
  const std::string dir = colmap_model("colmap_nan", "1 PINHOLE 640 480 nan 500 320 240\n",
                                       "1 1 0 0 0 0 0 5 1 a.png\n\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir), "is not a finite number ('nan')");
}

TEST(Colmap, ZeroQuaternionIsAnError) {
  const std::string dir =
      colmap_model("colmap_zero_quaternion", "1 PINHOLE 640 480 500 500 320 240\n",
                   "1 0 0 0 0 0 0 5 1 a.png\n\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir), "images.txt:1: zero quaternion");
}

TEST(Colmap, MissingPointsLinesAreAnError) {
  // One line per image: the second image line would be taken as points.
  const std::string dir =
      colmap_model("colmap_no_points_lines", "1 PINHOLE 640 480 500 500 320 240\n",
                   "1 1 0 0 0 0 0 5 1 a.png\n2 1 0 0 0 0 0 5 1 b.png\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir), "every image takes two lines");
}

// ------------------------------------------------------------ Bundler

namespace {

// Bundler's own projection (camera along -z, y up, from the image centre),
// moved to pixel-centre coordinates with the centre at ((W-1)/2, (H-1)/2).
Vec2 bundler_project(const Mat3& R, const Vec3& t, double f, double k1, double k2, int W, int H,
                     const Vec3& X) {
  const Vec3 P = R * X + t;
  EXPECT_LT(P.z(), 0) << "test point behind the Bundler camera";
  const Vec2 p(-P.x() / P.z(), -P.y() / P.z());
  const double r2 = p.squaredNorm();
  const double r = 1 + k1 * r2 + k2 * r2 * r2;
  return {f * p.x() * r + (W - 1) / 2.0, (H - 1) / 2.0 - f * p.y() * r};
}

// bundle.out + list.txt written to a temp folder (bad-input tests).
std::string bundler_files(const std::string& test_name, const std::string& bundle,
                          const std::string& list) {
  const fs::path dir = test::temp_dir(test_name);
  write_text(dir / "bundle.out", bundle);
  write_text(dir / "list.txt", list);
  return (dir / "bundle.out").string();
}

const char* kBundlerCamera = "800 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n";

}  // namespace

TEST(Bundler, SmallModelMatchesBundlerProjection) {
  // The list's paths are relative to image_dir, where the images are made.
  const fs::path images = test::temp_dir("bundler_small");
  write_blank_png(images / "images" / "a.png", 64, 48);
  write_blank_png(images / "c.png", 81, 61);  // b.png (unregistered) need not exist
  const Scene scene = io::read_bundler(test::data_dir() + "/bundler/small", images.string());
  EXPECT_EQ(scene.format, "bundler");
  ASSERT_EQ(scene.views.size(), 2u);
  EXPECT_TRUE(has_warning(scene, "1 of 3 cameras are unregistered")) << all_warnings(scene);
  EXPECT_EQ(scene.views[0].label, "images/a.png");
  EXPECT_EQ(scene.views[1].label, "c.png");
  EXPECT_EQ(scene.views[1].image_path, (images / "c.png").string());

  const PinholeCamera& a = scene.views[0].camera;
  EXPECT_EQ(a.width, 64);
  EXPECT_EQ(a.height, 48);
  EXPECT_EQ(a.cx, 31.5);
  EXPECT_EQ(a.cy, 23.5);
  const Mat3 R_c = (Mat3() << 0, 0, 1, 0, 1, 0, -1, 0, 0).finished();
  for (const Vec3& X : {Vec3(0.3, 0.4, 0.5), Vec3(-0.2, 0.1, -0.3), Vec3(0, 0, 0)}) {
    Vec2 expected = bundler_project(Mat3::Identity(), {0.1, -0.2, -5}, 800, 0, 0, 64, 48, X);
    Vec2 px = project_or_fail(a, X);
    EXPECT_NEAR(px.x(), expected.x(), 1e-9);
    EXPECT_NEAR(px.y(), expected.y(), 1e-9);
    expected = bundler_project(R_c, {0.5, 0.25, -6}, 650, -0.05, 0.01, 81, 61, X);
    px = project_or_fail(scene.views[1].camera, X);
    EXPECT_NEAR(px.x(), expected.x(), 1e-9);
    EXPECT_NEAR(px.y(), expected.y(), 1e-9);
  }
  // Bundler's +y (up) is our image up: a point above the target has smaller v.
  Vec2 centre, above;
  ASSERT_TRUE(a.project({-0.1, 0.2, 0}, &centre));
  ASSERT_TRUE(a.project({-0.1, 0.7, 0}, &above));
  EXPECT_NEAR(centre.y(), 23.5, 1e-9);
  EXPECT_LT(above.y(), centre.y());
  // A point behind Bundler's camera (P.z > 0) is behind ours.
  Vec2 unused;
  EXPECT_FALSE(a.project({0, 0, 10}, &unused));
}

TEST(Bundler, TruncatedFileIsAnError) {
  const std::string bundle =
      bundler_files("bundler_truncated",
                    std::string("# Bundle file v0.3\n2 0\n") + kBundlerCamera + "800 0 0\n1 0 0\n",
                    "a.png\nb.png\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_bundler(bundle),
                                "truncated: the file ends inside camera 1 of 2");
}

TEST(Bundler, ListCountMismatchIsAnError) {
  const std::string bundle = bundler_files(
      "bundler_count", std::string("# Bundle file v0.3\n2 0\n") + kBundlerCamera + kBundlerCamera,
      "a.png\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_bundler(bundle), "lists 1 images but");
}

TEST(Bundler, MissingImageOfRegisteredCameraIsAnError) {
  const std::string bundle =
      bundler_files("bundler_missing_image",
                    std::string("# Bundle file v0.3\n1 0\n") + kBundlerCamera, "a.png\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_bundler(bundle),
                                "list.txt:1: image of registered camera 0 not found");
}

TEST(Bundler, ImplausibleCameraCountIsAnError) {
  const std::string bundle =
      bundler_files("bundler_huge_count", "# Bundle file v0.3\n1000000000 0\n", "a.png\n");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_bundler(bundle),
                                "declares 1000000000 cameras but the file has only");
}
