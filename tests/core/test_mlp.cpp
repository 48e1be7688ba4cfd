// MeshLab project I/O. The reference for the camera is VCG's own projection
// (vcglib Shot::ConvertWorldToCameraCoordinates + Camera::Project +
// LocalToViewportPx), re-derived here from those formulas and independent
// of our conversion code:
//   q = Rv (X - C) with C = -TranslationVector; q.z = -q.z;
//   (mx, my) = FocalMm * (q.x, q.y) / q.z;
//   (px, py) = (mx / PixelSizeMm.x + CenterPx.x, my / PixelSizeMm.y + CenterPx.y)
// with the origin at the image's bottom-left CORNER, y up. A pixel-centre,
// top-left, y-down coordinate is then (px - 0.5, H - py - 0.5).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>

#include "box_scene.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"
#include "test_util.h"

using namespace meshnbv;
using test::num;
namespace fs = std::filesystem;

namespace {

struct VcgShot {
  Vec3 tra;       // TranslationVector (= -centre)
  Mat3 rot;       // upper 3x3 of RotationMatrix, rows = camera axes
  double focal_mm, pixel_mm_x, pixel_mm_y, center_x, center_y;
  int width, height;
};

Vec2 vcg_project_top_left(const VcgShot& s, const Vec3& X) {
  Vec3 q = s.rot * (X + s.tra);
  q.z() = -q.z();
  const double mx = s.focal_mm * q.x() / q.z(), my = s.focal_mm * q.y() / q.z();
  const double px = mx / s.pixel_mm_x + s.center_x, py = my / s.pixel_mm_y + s.center_y;
  return {px - 0.5, s.height - py - 0.5};
}

std::string raster_xml(const std::string& label, const VcgShot& s, const std::string& image) {
  std::string rot;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rot += num(s.rot(r, c)) + " ";
    rot += "0 ";
  }
  rot += "0 0 0 1";
  std::string xml = "  <MLRaster label=\"" + label + "\">\n   <VCGCamera TranslationVector=\"" +
                    num(s.tra.x()) + " " + num(s.tra.y()) + " " + num(s.tra.z()) +
                    " 1\" LensDistortion=\"0 0\" ViewportPx=\"" + std::to_string(s.width) + " " +
                    std::to_string(s.height) + "\" PixelSizeMm=\"" + num(s.pixel_mm_x) + " " +
                    num(s.pixel_mm_y) + "\" CenterPx=\"" + num(s.center_x) + " " +
                    num(s.center_y) + "\" FocalMm=\"" + num(s.focal_mm) +
                    "\" RotationMatrix=\"" + rot + "\" CameraType=\"0\"/>\n";
  if (!image.empty()) xml += "   <Plane semantic=\"1\" fileName=\"" + image + "\"/>\n";
  return xml + "  </MLRaster>\n";
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string tiny_mesh(const std::string& dir) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2}};
  const std::string path = dir + "/tri.ply";
  io::write_ply(m, path);
  return path;
}

std::vector<VcgShot> three_poses() {
  std::vector<VcgShot> shots;
  const Vec3 axes[3] = {Vec3(0.3, 1, 0.2), Vec3(-1, 0.4, 0.7), Vec3(0.1, -0.2, 1)};
  const double angles[3] = {0.7, 2.1, -1.3};
  const Vec3 centres[3] = {Vec3(1, 2, 3), Vec3(-4, 0.5, 1), Vec3(0.2, -3, -2)};
  for (int i = 0; i < 3; ++i) {
    VcgShot s;
    s.rot = Eigen::AngleAxisd(angles[i], axes[i].normalized()).toRotationMatrix();
    s.tra = -centres[i];
    s.focal_mm = 28.0 + 5 * i;
    s.pixel_mm_x = 0.0369161;
    s.pixel_mm_y = 0.0369161 * (1.0 + 0.01 * i);  // non-square pixels too
    s.width = 640 + 160 * i;
    s.height = 480 + 20 * i;
    s.center_x = 0.5 * s.width + 7.25 * i;
    s.center_y = 0.5 * s.height - 3.5 * i;
    shots.push_back(s);
  }
  return shots;
}

}  // namespace

TEST(Mlp, CamerasProjectLikeVcg) {
  const std::string dir = test::temp_dir("mlp_vcg");
  const auto shots = three_poses();
  std::string xml = "<!DOCTYPE MeshLabDocument>\n<MeshLabProject>\n <MeshGroup>\n"
                    "  <MLMesh label=\"tri\" filename=\"tri.ply\"/>\n </MeshGroup>\n <RasterGroup>\n";
  for (std::size_t i = 0; i < shots.size(); ++i)
    xml += raster_xml("r" + std::to_string(i), shots[i], "");
  xml += " </RasterGroup>\n</MeshLabProject>\n";
  tiny_mesh(dir);
  write_text(dir + "/p.mlp", xml);
  const Scene scene = io::read_mlp(dir + "/p.mlp");
  ASSERT_EQ(scene.views.size(), 3u);
  int checked = 0;
  for (std::size_t i = 0; i < shots.size(); ++i) {
    const PinholeCamera& cam = scene.views[i].camera;
    EXPECT_EQ(cam.width, shots[i].width);
    EXPECT_FALSE(scene.views[i].has_image());
    // Points in front of the VCG camera (along -z of its rotation rows).
    const Vec3 centre = -shots[i].tra;
    const Vec3 forward = -shots[i].rot.row(2).transpose();
    const Vec3 right = shots[i].rot.row(0).transpose(), up = shots[i].rot.row(1).transpose();
    for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(0.3, -0.2, 0), Vec3(-0.5, 0.4, 0)}) {
      const Vec3 X = centre + 4.0 * forward + offset.x() * right + offset.y() * up;
      Vec2 ours;
      ASSERT_TRUE(cam.project(X, &ours));
      const Vec2 vcg = vcg_project_top_left(shots[i], X);
      EXPECT_NEAR((ours - vcg).norm(), 0, 1e-7) << "pose " << i;
      // Above the optical axis in the world = above (smaller row) in the image.
      if (offset.y() > 0) {
        Vec2 axis_px;
        cam.project(centre + 4.0 * forward + offset.x() * right, &axis_px);
        EXPECT_LT(ours.y(), axis_px.y());
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
}

TEST(Mlp, RoundTripWithImagesAndCandidates) {
  const std::string dir = test::temp_dir("mlp_roundtrip");
  test::BoxSceneOptions options;
  options.views = 4;
  options.width = 64;
  options.height = 48;
  Scene scene = test::make_box_scene(options);
  scene.views[0].image_path = dir + "/img/a.png";
  scene.views[1].image_path = dir + "/img/b.png";
  fs::create_directories(dir + "/img");
  for (int i = 0; i < 2; ++i) test::render_box(options, scene.views[i].camera).save(scene.views[i].image_path);
  scene.views[1].camera.fy *= 1.02;  // non-square pixels survive
  io::SceneWriteOptions wo;
  io::write_scene(scene, dir + "/out/project.mlp", wo);
  ASSERT_TRUE(fs::exists(dir + "/out/project_mesh.ply"));
  const Scene back = io::read_scene(dir + "/out/project.mlp");
  ASSERT_EQ(back.views.size(), scene.views.size());
  EXPECT_EQ(back.mesh.num_faces(), scene.mesh.num_faces());
  for (std::size_t i = 0; i < scene.views.size(); ++i) {
    const PinholeCamera &a = scene.views[i].camera, &b = back.views[i].camera;
    EXPECT_EQ(back.views[i].label, scene.views[i].label);
    EXPECT_NEAR((a.R - b.R).norm(), 0, 1e-12);
    EXPECT_NEAR((a.t - b.t).norm(), 0, 1e-12);
    EXPECT_NEAR(a.fx, b.fx, 1e-9);
    EXPECT_NEAR(a.fy, b.fy, 1e-9);
    EXPECT_NEAR(a.cx, b.cx, 1e-12);
    EXPECT_NEAR(a.cy, b.cy, 1e-12);
    EXPECT_EQ(back.views[i].has_image(), i < 2);
  }
  EXPECT_EQ(fs::canonical(back.views[0].image_path), fs::canonical(scene.views[0].image_path));
  EXPECT_EQ(back.image(0)->width(), 64);
  // Paths in the project are relative to it, so a moved folder still opens.
  const std::string text = io::read_file(dir + "/out/project.mlp");
  EXPECT_NE(text.find("fileName=\"../img/a.png\""), std::string::npos) << text;
}

TEST(Mlp, RefusesToOverwrite) {
  const std::string dir = test::temp_dir("mlp_overwrite");
  Scene scene = test::make_box_scene();
  io::write_scene(scene, dir + "/p.mlp");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::write_scene(scene, dir + "/p.mlp"), "--overwrite");
  io::SceneWriteOptions wo;
  wo.overwrite = true;
  EXPECT_NO_THROW(io::write_scene(scene, dir + "/p.mlp", wo));
}

TEST(Mlp, MeshMatrixIsApplied) {
  const std::string dir = test::temp_dir("mlp_matrix");
  tiny_mesh(dir);
  write_text(dir + "/p.mlp",
             "<!DOCTYPE MeshLabDocument>\n<MeshLabProject><MeshGroup>"
             "<MLMesh label=\"tri\" filename=\"tri.ply\"><MLMatrix44>\n"
             "0 -1 0 10 \n1 0 0 20 \n0 0 2 30 \n0 0 0 1 \n</MLMatrix44></MLMesh>"
             "</MeshGroup><RasterGroup/></MeshLabProject>");
  const Scene scene = io::read_mlp(dir + "/p.mlp");
  ASSERT_EQ(scene.mesh.num_vertices(), 3u);
  EXPECT_NEAR((scene.mesh.vertices[1] - Vec3(10, 21, 30)).norm(), 0, 1e-12);
  EXPECT_NEAR((scene.mesh.vertices[2] - Vec3(9, 20, 30)).norm(), 0, 1e-12);
}

TEST(Mlp, BinaryCameraData) {
  // BinaryData="1": base64 of float32 arrays (MeshLab's optional encoding).
  // TranslationVector 0 0 -5, identity rotation, 640x480, f = 20 mm,
  // 0.04 mm pixels, centre (320, 240).
  const std::string dir = test::temp_dir("mlp_binary");
  tiny_mesh(dir);
  write_text(dir + "/p.mlp",
             "<MeshLabProject><MeshGroup><MLMesh filename=\"tri.ply\"/></MeshGroup><RasterGroup>"
             "<MLRaster label=\"b\"><VCGCamera BinaryData=\"1\" CameraType=\"0\" "
             "TranslationVector=\"AAAAAAAAAAAAAKDA\" "
             "RotationMatrix=\"AACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAACAPw==\" "
             "FocalMm=\"AACgQQ==\" PixelSizeMm=\"CtcjPQrXIz0=\" ViewportPx=\"gAIAAOABAAA=\" "
             "CenterPx=\"AACgQwAAcEM=\" LensDistortion=\"AAAAAAAAAAA=\"/></MLRaster>"
             "</RasterGroup></MeshLabProject>");
  const Scene scene = io::read_mlp(dir + "/p.mlp");
  ASSERT_EQ(scene.views.size(), 1u);
  const PinholeCamera& c = scene.views[0].camera;
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_NEAR(c.fx, 500.0, 1e-3);
  EXPECT_NEAR(c.cx, 319.5, 1e-9);
  EXPECT_NEAR(c.cy, 239.5, 1e-9);
  EXPECT_NEAR((c.center() - Vec3(0, 0, 5)).norm(), 0, 1e-6);
  EXPECT_NEAR((c.forward() - Vec3(0, 0, -1)).norm(), 0, 1e-6);
}

TEST(Mlp, MalformedXmlGivesLine) {
  const std::string dir = test::temp_dir("mlp_malformed");
  write_text(dir + "/p.mlp", "<MeshLabProject>\n<MeshGroup>\n<MLMesh filename=\"a.ply\"\n</MeshLabProject>");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_mlp(dir + "/p.mlp"), "malformed XML");
  write_text(dir + "/q.mlp", "<Other/>");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_mlp(dir + "/q.mlp"), "not a MeshLab project");
}

TEST(Mlp, BadCameraIsReported) {
  const std::string dir = test::temp_dir("mlp_badcam");
  tiny_mesh(dir);
  VcgShot s = three_poses()[0];
  s.focal_mm = 0;
  write_text(dir + "/zero.mlp", "<MeshLabProject><MeshGroup><MLMesh filename=\"tri.ply\"/></MeshGroup><RasterGroup>\n" +
                                    raster_xml("zf", s, "") + "</RasterGroup></MeshLabProject>");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_mlp(dir + "/zero.mlp"), "focal length must be positive");
  std::string nan_xml = raster_xml("nan", three_poses()[1], "");
  nan_xml.replace(nan_xml.find("TranslationVector=\"") + 19, 1, "nan 0");
  write_text(dir + "/nan.mlp", "<MeshLabProject><RasterGroup>\n" + nan_xml + "</RasterGroup></MeshLabProject>");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_mlp(dir + "/nan.mlp"), "not a finite number");
}

TEST(Mlp, MissingMeshFile) {
  const std::string dir = test::temp_dir("mlp_missing_mesh");
  write_text(dir + "/p.mlp", "<MeshLabProject><MeshGroup><MLMesh filename=\"gone.ply\"/></MeshGroup></MeshLabProject>");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_mlp(dir + "/p.mlp"), "gone.ply");
}
