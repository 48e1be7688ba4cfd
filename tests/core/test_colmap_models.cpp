// COLMAP models, text and binary, every camera model COLMAP 3.8 writes.
// The test writes the models itself (its own writers, from COLMAP's
// documented layout: doc/format.rst and src/base/reconstruction.cc of
// COLMAP 3.8) and projects with COLMAP's formulas written out below
// (src/base/camera_models.h), then compares with what our reader makes of
// the files, directly and after a JSON round trip.
//   COLMAP pixel = f * (x + dx) + c, with the top-left pixel centre at
//   (0.5, 0.5): ours is that minus 0.5 (docs/conventions.md).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"
#include "test_util.h"

using namespace meshnbv;
using test::json_round_trip;
namespace fs = std::filesystem;

namespace {

struct TestCamera {
  std::string model;
  int model_id;
  int width, height;
  std::vector<double> params;
};

struct TestImage {
  Eigen::Quaterniond q;  // world to camera
  Vec3 t;
  int camera_id;  // 1-based index into cameras
  std::string name;
  std::vector<Vec2> points2d;  // COLMAP pixels
};

struct TestPoint {
  Vec3 X;
  std::vector<std::pair<int, int>> track;  // (IMAGE_ID, POINT2D_IDX)
};

struct TestModel {
  std::vector<TestCamera> cameras;  // CAMERA_ID = index + 1
  std::vector<TestImage> images;    // IMAGE_ID = index + 1
  std::vector<TestPoint> points;
};

bool single_focal(const std::string& m) {
  return m == "SIMPLE_PINHOLE" || m == "SIMPLE_RADIAL" || m == "RADIAL" ||
         m == "SIMPLE_RADIAL_FISHEYE" || m == "RADIAL_FISHEYE";
}

// COLMAP 3.8's WorldToImage for (u, v) = (X/Z, Y/Z), written out per model.
Vec2 colmap_world_to_image(const TestCamera& cam, double u, double v) {
  const std::string& m = cam.model;
  const std::vector<double>& p = cam.params;
  const bool single = single_focal(m);
  const double fx = p[0], fy = single ? p[0] : p[1];
  const double cx = single ? p[1] : p[2], cy = single ? p[2] : p[3];
  const double* e = p.data() + (single ? 3 : 4);
  double x = u, y = v;
  const double r2 = u * u + v * v, r = std::sqrt(r2);
  if (m == "SIMPLE_RADIAL") {
    x = u + u * e[0] * r2, y = v + v * e[0] * r2;
  } else if (m == "RADIAL") {
    const double radial = e[0] * r2 + e[1] * r2 * r2;
    x = u + u * radial, y = v + v * radial;
  } else if (m == "OPENCV") {
    const double radial = e[0] * r2 + e[1] * r2 * r2;
    x = u + u * radial + 2 * e[2] * u * v + e[3] * (r2 + 2 * u * u);
    y = v + v * radial + 2 * e[3] * u * v + e[2] * (r2 + 2 * v * v);
  } else if (m == "FULL_OPENCV") {
    const double r4 = r2 * r2, r6 = r4 * r2;
    const double radial = (1 + e[0] * r2 + e[1] * r4 + e[4] * r6) /
                          (1 + e[5] * r2 + e[6] * r4 + e[7] * r6);
    x = u * radial + 2 * e[2] * u * v + e[3] * (r2 + 2 * u * u);
    y = v * radial + 2 * e[3] * u * v + e[2] * (r2 + 2 * v * v);
  } else if (m == "OPENCV_FISHEYE" || m == "SIMPLE_RADIAL_FISHEYE" || m == "RADIAL_FISHEYE") {
    const double th = std::atan(r), t2 = th * th;
    double thd = th;
    if (m == "OPENCV_FISHEYE")
      thd = th * (1 + e[0] * t2 + e[1] * t2 * t2 + e[2] * t2 * t2 * t2 + e[3] * t2 * t2 * t2 * t2);
    if (m == "SIMPLE_RADIAL_FISHEYE") thd = th * (1 + e[0] * t2);
    if (m == "RADIAL_FISHEYE") thd = th * (1 + e[0] * t2 + e[1] * t2 * t2);
    if (r > 1e-16) x = u * thd / r, y = v * thd / r;
  } else if (m == "THIN_PRISM_FISHEYE") {
    const double th = std::atan(r);
    const double uu = r > 1e-16 ? th * u / r : u, vv = r > 1e-16 ? th * v / r : v;
    const double s2 = uu * uu + vv * vv;
    const double radial = e[0] * s2 + e[1] * s2 * s2 + e[4] * s2 * s2 * s2 + e[5] * s2 * s2 * s2 * s2;
    x = uu + uu * radial + 2 * e[2] * uu * vv + e[3] * (s2 + 2 * uu * uu) + e[6] * s2;
    y = vv + vv * radial + 2 * e[3] * uu * vv + e[2] * (s2 + 2 * vv * vv) + e[7] * s2;
  }  // SIMPLE_PINHOLE, PINHOLE, FOV with omega = 0: no distortion
  return {fx * x + cx, fy * y + cy};
}

Vec2 colmap_project(const TestModel& model, const TestImage& image, const Vec3& X) {
  const Vec3 xc = image.q.toRotationMatrix() * X + image.t;
  return colmap_world_to_image(model.cameras[std::size_t(image.camera_id - 1)], xc.x() / xc.z(),
                               xc.y() / xc.z());
}

// ---- independent writers

void write_text_model(const TestModel& m, const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream cams(dir / "cameras.txt"), imgs(dir / "images.txt"), pts(dir / "points3D.txt");
  cams << std::setprecision(17) << "# CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
  for (std::size_t i = 0; i < m.cameras.size(); ++i) {
    const TestCamera& c = m.cameras[i];
    cams << i + 1 << ' ' << c.model << ' ' << c.width << ' ' << c.height;
    for (double p : c.params) cams << ' ' << p;
    cams << '\n';
  }
  // Which 3-D point each 2-D point belongs to (-1: none).
  std::map<std::pair<int, int>, int> owner;
  for (std::size_t j = 0; j < m.points.size(); ++j)
    for (const auto& [image, idx] : m.points[j].track) owner[{image, idx}] = int(j) + 1;
  imgs << std::setprecision(17) << "# IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n";
  for (std::size_t i = 0; i < m.images.size(); ++i) {
    const TestImage& im = m.images[i];
    imgs << i + 1 << ' ' << im.q.w() << ' ' << im.q.x() << ' ' << im.q.y() << ' ' << im.q.z() << ' '
         << im.t.x() << ' ' << im.t.y() << ' ' << im.t.z() << ' ' << im.camera_id << ' ' << im.name
         << '\n';
    for (std::size_t k = 0; k < im.points2d.size(); ++k) {
      const auto it = owner.find({int(i) + 1, int(k)});
      imgs << (k ? " " : "") << im.points2d[k].x() << ' ' << im.points2d[k].y() << ' '
           << (it == owner.end() ? -1 : it->second);
    }
    imgs << '\n';
  }
  pts << std::setprecision(17) << "# POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[]\n";
  for (std::size_t j = 0; j < m.points.size(); ++j) {
    const TestPoint& p = m.points[j];
    pts << j + 1 << ' ' << p.X.x() << ' ' << p.X.y() << ' ' << p.X.z() << " 128 128 128 0.5";
    for (const auto& [image, idx] : p.track) pts << ' ' << image << ' ' << idx;
    pts << '\n';
  }
}

template <typename T>
void put(std::ofstream& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // the test machine is little-endian, as the format
  out.write(bytes, sizeof(T));
}

void write_binary_model(const TestModel& m, const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream cams(dir / "cameras.bin", std::ios::binary);
  put<std::uint64_t>(cams, m.cameras.size());
  for (std::size_t i = 0; i < m.cameras.size(); ++i) {
    const TestCamera& c = m.cameras[i];
    put<std::uint32_t>(cams, std::uint32_t(i + 1));
    put<std::int32_t>(cams, c.model_id);
    put<std::uint64_t>(cams, std::uint64_t(c.width));
    put<std::uint64_t>(cams, std::uint64_t(c.height));
    for (double p : c.params) put<double>(cams, p);
  }
  std::map<std::pair<int, int>, std::uint64_t> owner;
  for (std::size_t j = 0; j < m.points.size(); ++j)
    for (const auto& [image, idx] : m.points[j].track) owner[{image, idx}] = j + 1;
  std::ofstream imgs(dir / "images.bin", std::ios::binary);
  put<std::uint64_t>(imgs, m.images.size());
  for (std::size_t i = 0; i < m.images.size(); ++i) {
    const TestImage& im = m.images[i];
    put<std::uint32_t>(imgs, std::uint32_t(i + 1));
    for (double v : {im.q.w(), im.q.x(), im.q.y(), im.q.z(), im.t.x(), im.t.y(), im.t.z()})
      put<double>(imgs, v);
    put<std::uint32_t>(imgs, std::uint32_t(im.camera_id));
    imgs.write(im.name.c_str(), std::streamsize(im.name.size() + 1));  // with its NUL
    put<std::uint64_t>(imgs, im.points2d.size());
    for (std::size_t k = 0; k < im.points2d.size(); ++k) {
      put<double>(imgs, im.points2d[k].x());
      put<double>(imgs, im.points2d[k].y());
      const auto it = owner.find({int(i) + 1, int(k)});
      put<std::uint64_t>(imgs, it == owner.end() ? ~std::uint64_t(0) : it->second);
    }
  }
  std::ofstream pts(dir / "points3D.bin", std::ios::binary);
  put<std::uint64_t>(pts, m.points.size());
  for (std::size_t j = 0; j < m.points.size(); ++j) {
    const TestPoint& p = m.points[j];
    put<std::uint64_t>(pts, j + 1);
    for (int k = 0; k < 3; ++k) put<double>(pts, p.X(k));
    for (int k = 0; k < 3; ++k) put<std::uint8_t>(pts, 128);
    put<double>(pts, 0.5);
    put<std::uint64_t>(pts, p.track.size());
    for (const auto& [image, idx] : p.track) {
      put<std::uint32_t>(pts, std::uint32_t(image));
      put<std::uint32_t>(pts, std::uint32_t(idx));
    }
  }
}

// ---- scenes

// Images on a ring around the origin, looking at it; points in a ball of
// radius 1, observed (with Gaussian noise `noise_px`) where they project
// inside the image.
TestModel ring_model(const std::vector<TestCamera>& cameras, int num_images, int num_points,
                     double noise_px, unsigned seed) {
  TestModel m;
  m.cameras = cameras;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_px);
  std::uniform_real_distribution<double> ball(-1, 1);
  for (int i = 0; i < num_images; ++i) {
    const double a = 2 * M_PI * i / num_images;
    const auto cam = PinholeCamera::look_at({6 * std::cos(a), 6 * std::sin(a), 1.5 + 0.2 * i},
                                            {0.1, -0.05, 0}, {0, 0, 1}, 1, 1, 0, 0, 1, 1);
    TestImage im;
    im.q = Eigen::Quaterniond(cam.R);
    im.t = cam.t;
    im.camera_id = 1 + i % int(cameras.size());
    im.name = "img_" + std::to_string(i) + ".jpg";
    m.images.push_back(im);
  }
  for (int j = 0; j < num_points; ++j) {
    TestPoint p;
    p.X = Vec3(ball(rng), ball(rng), ball(rng));
    for (std::size_t i = 0; i < m.images.size(); ++i) {
      TestImage& im = m.images[i];
      const TestCamera& c = m.cameras[std::size_t(im.camera_id - 1)];
      const Vec2 px = colmap_project(m, im, p.X);
      if (px.x() < 0 || px.y() < 0 || px.x() > c.width || px.y() > c.height) continue;
      p.track.emplace_back(int(i) + 1, int(im.points2d.size()));
      im.points2d.push_back(px + Vec2(noise(rng), noise(rng)));
    }
    m.points.push_back(p);
  }
  return m;
}

std::vector<TestCamera> opencv_cameras() {
  return {{"OPENCV", 4, 1600, 1200, {1450.25, 1447.5, 801.3, 598.7, -0.112, 0.0451, 0.00123, -0.00087}},
          {"OPENCV", 4, 1200, 900, {1010.0, 1012.5, 603.1, 449.2, 0.083, -0.021, -0.0009, 0.0014}}};
}

void expect_identical_camera(const PinholeCamera& a, const PinholeCamera& b) {
  const double tol = 1e-12;
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.lens, b.lens);
  for (auto p : {&PinholeCamera::fx, &PinholeCamera::fy, &PinholeCamera::cx, &PinholeCamera::cy,
                 &PinholeCamera::k1, &PinholeCamera::k2, &PinholeCamera::k3, &PinholeCamera::k4,
                 &PinholeCamera::k5, &PinholeCamera::k6, &PinholeCamera::p1, &PinholeCamera::p2,
                 &PinholeCamera::skew})
    EXPECT_NEAR(a.*p, b.*p, tol * std::max(1.0, std::abs(b.*p)));
  EXPECT_LT((a.R - b.R).norm(), tol);
  EXPECT_LT((a.t - b.t).norm(), tol * std::max(1.0, b.t.norm()));
}

// Random points in front of every image project, through `scene`, to
// COLMAP's pixel minus half a pixel, to 1e-6 px.
void expect_projects_like_colmap(const Scene& scene, const TestModel& m, unsigned seed) {
  ASSERT_EQ(scene.views.size(), m.images.size());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lateral(-0.5, 0.5), depth(1.0, 30.0);
  for (std::size_t i = 0; i < m.images.size(); ++i) {
    const PinholeCamera& cam = scene.views[i].camera;
    for (int k = 0; k < 50; ++k) {
      const double z = depth(rng);
      const Vec3 X = cam.camera_to_world(Vec3(lateral(rng) * z, lateral(rng) * z, z));
      Vec2 ours;
      ASSERT_TRUE(cam.project(X, &ours));
      const Vec2 expected = colmap_project(m, m.images[i], X) - Vec2(0.5, 0.5);
      EXPECT_NEAR(ours.x(), expected.x(), 1e-6) << scene.views[i].label;
      EXPECT_NEAR(ours.y(), expected.y(), 1e-6) << scene.views[i].label;
    }
  }
}

}  // namespace

TEST(ColmapModels, OpencvBinaryAndTextGiveTheSameCameras) {
  const TestModel m = ring_model(opencv_cameras(), 8, 400, 0.25, 7);
  const fs::path dir = test::temp_dir("colmap_opencv_bin_txt");
  write_text_model(m, dir / "text");
  write_binary_model(m, dir / "binary");
  EXPECT_EQ(io::detect_scene_format((dir / "binary").string()), io::SceneFormat::Colmap);
  const Scene text = io::read_scene((dir / "text").string());
  const Scene binary = io::read_scene((dir / "binary").string());
  EXPECT_EQ(text.producer, "COLMAP (text model)");
  EXPECT_EQ(binary.producer, "COLMAP (binary model)");
  ASSERT_EQ(text.views.size(), binary.views.size());
  for (std::size_t i = 0; i < text.views.size(); ++i) {
    EXPECT_EQ(text.views[i].label, binary.views[i].label);
    expect_identical_camera(text.views[i].camera, binary.views[i].camera);
  }
  // The recorded observations carry 0.25 px of noise: through our cameras
  // they reproject with a median error of about 0.29 px (1.18 sigma).
  for (const Scene* s : {&text, &binary}) {
    ASSERT_EQ(s->sparse_points.size(), 400u);
    const ReprojectionStats r = reprojection_error(*s);
    EXPECT_GT(r.observations, 1000u);
    EXPECT_EQ(r.behind, 0u);
    EXPECT_LE(r.median, 0.5);
    EXPECT_GT(r.median, 0.15);
  }
  expect_projects_like_colmap(binary, m, 1);
}

TEST(ColmapModels, NoiseFreeObservationsReprojectExactly) {
  const TestModel m = ring_model(opencv_cameras(), 6, 200, 0.0, 8);
  const fs::path dir = test::temp_dir("colmap_opencv_exact");
  write_binary_model(m, dir);
  const ReprojectionStats r = reprojection_error(io::read_colmap(dir.string()));
  EXPECT_GT(r.observations, 500u);
  EXPECT_LT(r.max, 1e-6);  // a missing half-pixel shift would show as 0.7 px
}

TEST(ColmapModels, EveryExactModelProjectsLikeColmap) {
  const std::vector<TestCamera> models = {
      {"SIMPLE_PINHOLE", 0, 1000, 800, {900, 501.2, 398.9}},
      {"PINHOLE", 1, 1000, 800, {900, 905, 501.2, 398.9}},
      {"SIMPLE_RADIAL", 2, 1000, 800, {900, 501.2, 398.9, -0.09}},
      {"RADIAL", 3, 1000, 800, {900, 501.2, 398.9, -0.09, 0.02}},
      {"OPENCV", 4, 1000, 800, {900, 905, 501.2, 398.9, -0.09, 0.02, 0.0011, -0.0007}},
      {"OPENCV_FISHEYE", 5, 1000, 800, {420, 421, 501.2, 398.9, 0.03, -0.011, 0.004, -0.0008}},
      {"FULL_OPENCV", 6, 1000, 800,
       {900, 905, 501.2, 398.9, 0.3, -0.1, 0.0011, -0.0007, 0.02, 0.42, -0.05, 0.01}},
      {"FOV", 7, 1000, 800, {900, 905, 501.2, 398.9, 0.0}},
      {"SIMPLE_RADIAL_FISHEYE", 8, 1000, 800, {420, 501.2, 398.9, 0.025}},
      {"RADIAL_FISHEYE", 9, 1000, 800, {420, 501.2, 398.9, 0.025, -0.004}},
      {"THIN_PRISM_FISHEYE", 10, 1000, 800,
       {420, 421, 501.2, 398.9, 0.03, -0.011, 0, 0, 0.004, -0.0008, 0, 0}},
  };
  for (const TestCamera& cam : models) {
    SCOPED_TRACE(cam.model);
    const TestModel m = ring_model({cam}, 3, 0, 0.0, 9);
    const fs::path dir = test::temp_dir("colmap_model_" + cam.model);
    write_text_model(m, dir / "text");
    write_binary_model(m, dir / "binary");
    const Scene text = io::read_colmap((dir / "text").string());
    const Scene binary = io::read_colmap((dir / "binary").string());
    const Scene json = json_round_trip(binary, "colmap_model_json_" + cam.model);
    for (const Scene* s : {&text, &binary, &json}) expect_projects_like_colmap(*s, m, 2);
    // And back out: our writer picks a model that holds the camera exactly.
    Scene out = binary;
    for (auto& v : out.views) v.image_path.clear();
    io::write_colmap(out, (dir / "written").string(), false);
    expect_projects_like_colmap(io::read_colmap((dir / "written").string()), m, 3);
  }
}

TEST(ColmapModels, TruncatedBinaryModelIsAnErrorAtEveryLength) {
  const TestModel m = ring_model(opencv_cameras(), 3, 20, 0.1, 10);
  const fs::path dir = test::temp_dir("colmap_truncated_bin");
  write_binary_model(m, dir / "good");
  for (const char* file : {"cameras.bin", "images.bin", "points3D.bin"}) {
    std::ifstream in(dir / "good" / file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (std::size_t n = 0; n < bytes.size(); n += 7) {
      const fs::path bad = dir / "bad";
      fs::remove_all(bad);
      fs::copy(dir / "good", bad);
      std::ofstream(bad / file, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(n));
      EXPECT_THROW(io::read_colmap(bad.string()), Error) << file << " cut at " << n;
    }
  }
}

TEST(ColmapModels, UnknownModelIdIsAnErrorNamingIt) {
  TestModel m = ring_model(opencv_cameras(), 2, 0, 0.0, 11);
  m.cameras[0].model_id = 11;
  const fs::path dir = test::temp_dir("colmap_bad_model_id");
  write_binary_model(m, dir);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_colmap(dir.string()), "unknown camera model id 11");
}

TEST(ColmapModels, SkewCannotBeWritten) {
  Scene scene;
  View v;
  v.label = "a";
  v.camera = PinholeCamera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 500, 500, 320, 240, 640, 480);
  v.camera.skew = 1.5;
  scene.views.push_back(v);
  MESHNBV_EXPECT_ERROR_CONTAINS(
      io::write_colmap(scene, test::temp_dir("colmap_skew") + "/model", false),
      "view 0 ('a'): a camera with skew");
}
