// vcg::Shot (MeshLab's raster camera) <-> PinholeCamera, checked against
// vcglib's own projection. Conventions (docs/conventions.md): ours has
// integer pixel coordinates at pixel centres with the origin top-left;
// Shot::Project gives viewport pixels with the origin at the bottom-left
// corner, y up. So u = px - 0.5, v = H - py - 0.5.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <QDomDocument>
#include <QString>
#include <QStringList>

#include <gtest/gtest.h>
#include <vcg/math/shot.h>
#include <wrap/qt/shot_qt.h>

#include "meshlab_test_support.h"
#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"
#include "shot_conversion.h"

using namespace meshnbv;
using meshnbv::meshlab::camera_from_shot;
using meshnbv::meshlab::decimal;
using meshnbv::meshlab::shot_from_camera;

namespace {

// A shot built with vcglib's own API: non-square pixels, principal point
// off centre, an oblique pose.
vcg::Shot<float> vcg_shot(const vcg::Point3f& eye, const vcg::Point3f& target, const vcg::Point3f& up) {
  vcg::Shot<float> shot;
  shot.Intrinsics.cameraType = 0;
  shot.Intrinsics.FocalMm = 8.5f;
  shot.Intrinsics.PixelSizeMm = vcg::Point2f(0.0100f, 0.0108f);
  shot.Intrinsics.ViewportPx = vcg::Point2i(640, 480);
  shot.Intrinsics.CenterPx = vcg::Point2f(331.25f, 229.5f);
  shot.Intrinsics.DistorCenterPx = shot.Intrinsics.CenterPx;
  shot.SetViewPoint(eye);
  shot.LookAt(target, up);
  return shot;
}

// Compares our projection of random points with Shot::Project.
void expect_projects_like(const PinholeCamera& cam, const vcg::Shot<float>& shot, double tolerance_px) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-12.0, 12.0);  // some behind the cameras
  int in_front = 0, behind = 0;  // in front: projecting near the image
  for (int i = 0; i < 500; ++i) {
    const Vec3 X(d(rng), d(rng), d(rng));
    const vcg::Point3f p(float(X.x()), float(X.y()), float(X.z()));
    Vec2 uv;
    const bool front = cam.project(X, &uv);
    ASSERT_EQ(front, shot.Depth(p) > 0) << "point " << X.transpose();
    if (!front) {
      ++behind;
      continue;
    }
    // Far outside the image float's precision (VCG's side) is all that is compared.
    if (uv.x() < -cam.width || uv.x() > 2 * cam.width || uv.y() < -cam.height || uv.y() > 2 * cam.height)
      continue;
    ++in_front;
    const vcg::Point2f px = shot.Project(p);
    EXPECT_NEAR(uv.x(), px[0] - 0.5, tolerance_px) << "point " << X.transpose();
    EXPECT_NEAR(uv.y(), cam.height - px[1] - 0.5, tolerance_px) << "point " << X.transpose();
    EXPECT_NEAR(cam.depth(X), shot.Depth(p), 1e-4);
  }
  EXPECT_GT(in_front, 100);
  EXPECT_GT(behind, 0);
}

}  // namespace

TEST(CameraConversion, ProjectsLikeShotProject) {
  const vcg::Point3f eyes[] = {{4.f, -6.f, 3.f}, {-2.f, 5.f, -7.f}, {0.5f, 0.2f, 9.f}};
  const vcg::Point3f targets[] = {{0.3f, 0.1f, -0.2f}, {1.f, -1.f, 0.5f}, {0.f, 0.f, 0.f}};
  const vcg::Point3f ups[] = {{0.f, 0.f, 1.f}, {0.2f, 1.f, 0.1f}, {0.f, 1.f, 0.f}};
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE("pose " + std::to_string(k));
    const vcg::Shot<float> shot = vcg_shot(eyes[k], targets[k], ups[k]);
    const PinholeCamera cam = camera_from_shot(shot, "test shot");
    EXPECT_EQ(cam.width, 640);
    EXPECT_EQ(cam.height, 480);
    EXPECT_NEAR(cam.fx, 850.0, 1e-3);
    EXPECT_NEAR(cam.fy, 8.5 / 0.0108, 1e-3);
    EXPECT_NEAR(cam.cx, 330.75, 1e-6);
    EXPECT_NEAR(cam.cy, 480 - 229.5 - 0.5, 1e-6);
    const vcg::Point3f c = shot.GetViewPoint();
    EXPECT_LT((cam.center() - Vec3(c[0], c[1], c[2])).norm(), 1e-5);
    // Shot::GetViewDir() is the shot's +z axis; the camera looks along -z.
    const vcg::Point3f z = shot.GetViewDir();
    EXPECT_LT((cam.forward() + Vec3(z[0], z[1], z[2]).normalized()).norm(), 1e-6);
    expect_projects_like(cam, shot, 2e-3);
  }
}

TEST(CameraConversion, ShotFromCameraProjectsLikeTheCamera) {
  const PinholeCamera cam = PinholeCamera::look_at(Vec3(5, -4, 2.5), Vec3(0.2, 0.1, 0.3),
                                                   Vec3(0, 0, 1), 900.0, 870.0, 310.3, 250.8, 640, 512);
  const vcg::Shot<float> shot = shot_from_camera(cam);
  expect_projects_like(cam, shot, 2e-3);
  const PinholeCamera back = camera_from_shot(shot);
  EXPECT_NEAR(back.fx, cam.fx, 1e-3);
  EXPECT_NEAR(back.fy, cam.fy, 1e-3);
  EXPECT_NEAR(back.cx, cam.cx, 1e-4);
  EXPECT_NEAR(back.cy, cam.cy, 1e-4);
  EXPECT_LT((back.center() - cam.center()).norm(), 1e-5);
  EXPECT_LT((back.R - cam.R).cwiseAbs().maxCoeff(), 1e-6);
}

// A camera MeshLab read from a project's text gives exactly the camera the
// core reads from the same text (floats through decimal()).
TEST(CameraConversion, EqualsCoreReadingOfTheSameMlpText) {
  const PinholeCamera truth = PinholeCamera::look_at(Vec3(-7.1, 3.3, 4.2), Vec3(0.5, -0.4, 0.9),
                                                     Vec3(0.1, 0.2, 1), 1234.5, 1201.7, 652.3,
                                                     470.9, 1280, 960);
  // MeshLab writes 6 significant digits (QString::arg(float)).
  auto g = [](double v) { return QString::number(v, 'g', 6); };
  const Vec3 c = truth.center();
  QString rot;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) rot += g((r == 0 ? 1 : -1) * truth.R(r, k)) + " ";
    rot += "0 ";
  }
  rot += "0 0 0 1";
  const QString camera = QString(
      "<VCGCamera TranslationVector=\"%1 %2 %3 1\" RotationMatrix=\"%4\" CameraType=\"0\" "
      "BinaryData=\"0\" FocalMm=\"%5\" LensDistortion=\"0 0\" PixelSizeMm=\"0.0369161 %6\" "
      "ViewportPx=\"1280 960\" CenterPx=\"%7 %8\"/>")
      .arg(g(-c.x()), g(-c.y()), g(-c.z()), rot, g(truth.fx * 0.0369161),
           g(truth.fx * 0.0369161 / truth.fy), g(truth.cx + 0.5), g(960 - truth.cy - 0.5));
  const std::filesystem::path dir = meshlab_test::scratch_dir("camera_mlp_text");
  const std::string mlp = (dir / "one.mlp").string();
  std::ofstream(mlp) << "<!DOCTYPE MeshLabDocument>\n<MeshLabProject>\n <MeshGroup/>\n"
                        " <RasterGroup>\n  <MLRaster label=\"a\">\n   "
                     << camera.toStdString() << "\n  </MLRaster>\n </RasterGroup>\n</MeshLabProject>\n";
  const Scene scene = io::read_scene(mlp);
  std::filesystem::remove_all(dir);
  ASSERT_EQ(scene.views.size(), 1u);
  const PinholeCamera& core = scene.views[0].camera;

  QDomDocument doc;
  ASSERT_TRUE(doc.setContent(camera));
  vcg::Shot<float> shot;
  ASSERT_TRUE(ReadShotFromQDomNode(shot, doc.documentElement()));
  const PinholeCamera ours = camera_from_shot(shot);
  EXPECT_EQ(ours.width, core.width);
  EXPECT_EQ(ours.height, core.height);
  EXPECT_EQ(ours.fx, core.fx);
  EXPECT_EQ(ours.fy, core.fy);
  EXPECT_EQ(ours.cx, core.cx);
  EXPECT_EQ(ours.cy, core.cy);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(ours.R(r, k), core.R(r, k)) << r << "," << k;
  for (int r = 0; r < 3; ++r) EXPECT_EQ(ours.t[r], core.t[r]) << r;
}

TEST(CameraConversion, DecimalGivesTheShortestDecimalOfAFloat) {
  EXPECT_EQ(decimal(0.33f), 0.33);
  EXPECT_EQ(decimal(0.6f), 0.6);
  EXPECT_EQ(decimal(80.0f), 80.0);
  EXPECT_EQ(decimal(-10.0f), -10.0);
  EXPECT_EQ(decimal(10.23049f), 10.23049);
  EXPECT_EQ(decimal(0.0369161f), 0.0369161);
  EXPECT_EQ(decimal(-0.242845f), -0.242845);
  EXPECT_TRUE(std::isnan(decimal(std::nanf(""))));
}

TEST(CameraConversion, RejectsDistortionAndOrthographicCameras) {
  vcg::Shot<float> shot = vcg_shot({4.f, -6.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f});
  shot.Intrinsics.k[0] = 0.01f;
  EXPECT_THROW(camera_from_shot(shot, "distorted"), Error);
  shot.Intrinsics.k[0] = 0.f;
  shot.Intrinsics.cameraType = 1;
  EXPECT_THROW(camera_from_shot(shot, "ortho"), Error);
  shot.Intrinsics.cameraType = 0;
  shot.Intrinsics.PixelSizeMm = vcg::Point2f(0.f, 0.01f);
  EXPECT_THROW(camera_from_shot(shot, "no pixel size"), Error);
}
