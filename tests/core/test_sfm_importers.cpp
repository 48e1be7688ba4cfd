// Metashape cameras XML, OpenMVG sfm_data.json, AliceVision sfm.json: each
// test writes the file itself from parameters in the tool's own terms, with
// the tool's documented projection written out here, and checks that the
// scene we read (and its JSON round trip) projects random points to the
// same pixels, to 1e-6 px.
//   Metashape (manual, appendix "Camera models", frame and fisheye):
//     x' = x (1 + K1 r^2 + K2 r^4 + K3 r^6 + K4 r^8) + P1 (r^2 + 2x^2) + 2 P2 x y
//     y' = y (1 + ...) + P2 (r^2 + 2y^2) + 2 P1 x y
//     u = W/2 + cx + x' (f + B1) + y' B2, v = H/2 + cy + y' f; top-left pixel
//     centre at (0.5, 0.5); fisheye: (x, y) scaled to theta = atan r first.
//     Camera to world = chunk [sR | T] * camera transform.
//   OpenMVG / AliceVision Brown: x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6)
//     + t2 (r^2 + 2x^2) + 2 t1 x y, y_d likewise with t1, t2 exchanged;
//     fisheye: theta_d = theta (1 + k1 th^2 + ... + k4 th^8); pixel = f x_d + pp;
//     x_cam = R (X - C).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "meshnbv/error.h"
#include "meshnbv/io/scene_io.h"
#include "test_util.h"

using namespace meshnbv;
using test::num;
using test::json_round_trip;
namespace fs = std::filesystem;

namespace {

using ProjectFn = std::function<Vec2(std::size_t view, const Vec3& X)>;

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

Vec2 radial_tangential(const Vec2& n, double k1, double k2, double k3, double k4, double a,
                       double b) {
  // x' = x (1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8) + a (r^2 + 2x^2) + 2 b x y
  // y' = y (...) + b (r^2 + 2y^2) + 2 a x y
  const double x = n.x(), y = n.y(), r2 = x * x + y * y;
  const double radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2 + k4 * r2 * r2 * r2 * r2;
  return {x * radial + a * (r2 + 2 * x * x) + 2 * b * x * y,
          y * radial + b * (r2 + 2 * y * y) + 2 * a * x * y};
}

Vec2 to_angle(const Vec2& n) {
  const double r = n.norm();
  return r > 0 ? Vec2(n * (std::atan(r) / r)) : n;
}

// Random points in front of each view, within ~25 degrees of its axis.
void expect_projects_like(const Scene& scene, const ProjectFn& expected, std::size_t views,
                          double tol = 1e-6) {
  ASSERT_EQ(scene.views.size(), views);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> lateral(-0.45, 0.45), depth(0.5, 40.0);
  for (std::size_t i = 0; i < views; ++i) {
    const PinholeCamera& cam = scene.views[i].camera;
    for (int k = 0; k < 60; ++k) {
      const double z = depth(rng);
      const Vec3 X = cam.camera_to_world(Vec3(lateral(rng) * z, lateral(rng) * z, z));
      Vec2 ours;
      ASSERT_TRUE(cam.project(X, &ours));
      const Vec2 want = expected(i, X);
      EXPECT_NEAR(ours.x(), want.x(), tol) << scene.views[i].label;
      EXPECT_NEAR(ours.y(), want.y(), tol) << scene.views[i].label;
    }
  }
}

// ------------------------------------------------------------- Metashape

struct MsSensor {
  std::string type;  // frame | fisheye
  int W, H;
  double f, cx, cy, b1, b2, k1, k2, k3, k4, p1, p2;
};

struct MsCamera {
  int sensor;
  std::string label;
  Eigen::Matrix4d to_chunk;  // camera to chunk
  std::string component;     // "" = none
};

struct MsChunk {
  std::vector<MsSensor> sensors;
  std::vector<MsCamera> cameras;
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  double scale = 1;
  Eigen::Matrix4d component = Eigen::Matrix4d::Identity();  // component "0"
  std::string reference;  // <reference> WKT; empty = none
};

Eigen::Matrix4d similarity(const Mat3& R, const Vec3& T, double s) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = s * R;
  m.topRightCorner<3, 1>() = T;
  return m;
}

std::string ms_xml(const MsChunk& c) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<document version=\"1.5.0\">\n <chunk label=\"Chunk 1\">\n  <sensors>\n";
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    const MsSensor& s = c.sensors[i];
    x << "   <sensor id=\"" << i << "\" label=\"cam" << i << "\" type=\"" << s.type << "\">\n"
      << "    <resolution width=\"" << s.W << "\" height=\"" << s.H << "\"/>\n"
      << "    <calibration type=\"" << s.type << "\" class=\"initial\"><resolution width=\"" << s.W
      << "\" height=\"" << s.H << "\"/><f>" << num(s.f * 1.1) << "</f></calibration>\n"
      << "    <calibration type=\"" << s.type << "\" class=\"adjusted\">\n"
      << "     <resolution width=\"" << s.W << "\" height=\"" << s.H << "\"/>\n"
      << "     <f>" << num(s.f) << "</f><cx>" << num(s.cx) << "</cx><cy>" << num(s.cy) << "</cy>"
      << "<b1>" << num(s.b1) << "</b1><b2>" << num(s.b2) << "</b2><k1>" << num(s.k1) << "</k1><k2>"
      << num(s.k2) << "</k2><k3>" << num(s.k3) << "</k3><k4>" << num(s.k4) << "</k4><p1>"
      << num(s.p1) << "</p1><p2>" << num(s.p2) << "</p2>\n    </calibration>\n   </sensor>\n";
  }
  x << "  </sensors>\n  <components><component id=\"0\"><transform><rotation>";
  for (int i = 0; i < 9; ++i) x << num(c.component(i / 3, i % 3) / std::cbrt(c.component.topLeftCorner<3, 3>().determinant())) << ' ';
  x << "</rotation><translation>" << num(c.component(0, 3)) << ' ' << num(c.component(1, 3)) << ' '
    << num(c.component(2, 3)) << "</translation><scale>"
    << num(std::cbrt(c.component.topLeftCorner<3, 3>().determinant())) << "</scale></transform></component></components>\n";
  x << "  <cameras>\n   <group id=\"0\" label=\"folder\" type=\"folder\">\n";
  for (std::size_t i = 0; i < c.cameras.size(); ++i) {
    const MsCamera& cam = c.cameras[i];
    x << "    <camera id=\"" << i << "\" sensor_id=\"" << cam.sensor << "\" label=\"" << cam.label << "\"";
    if (!cam.component.empty()) x << " component_id=\"" << cam.component << "\"";
    x << "><transform>";
    for (int k = 0; k < 16; ++k) x << num(cam.to_chunk(k / 4, k % 4)) << ' ';
    x << "</transform></camera>\n";
  }
  x << "   </group>\n   <camera id=\"99\" sensor_id=\"0\" label=\"unaligned\"/>\n  </cameras>\n";
  x << "  <transform><rotation locked=\"false\">";
  for (int i = 0; i < 9; ++i) x << num(c.rotation(i / 3, i % 3)) << ' ';
  x << "</rotation><translation>" << num(c.translation.x()) << ' ' << num(c.translation.y()) << ' '
    << num(c.translation.z()) << "</translation><scale>" << num(c.scale) << "</scale></transform>\n";
  if (!c.reference.empty()) x << "  <reference>" << c.reference << "</reference>\n";
  x << " </chunk>\n</document>\n";
  return x.str();
}

Vec2 ms_project(const MsChunk& c, const MsCamera& cam, const Vec3& X) {
  Eigen::Matrix4d to_world = similarity(c.rotation, c.translation, c.scale) *
                             (cam.component.empty() ? Eigen::Matrix4d::Identity() : c.component) *
                             cam.to_chunk;
  const Vec3 xc = to_world.inverse().topLeftCorner<3, 4>() * X.homogeneous();
  const MsSensor& s = c.sensors[std::size_t(cam.sensor)];
  Vec2 n(xc.x() / xc.z(), xc.y() / xc.z());
  if (s.type == "fisheye") n = to_angle(n);
  const Vec2 d = radial_tangential(n, s.k1, s.k2, s.k3, s.k4, s.p1, s.p2);
  const Vec2 metashape(s.W * 0.5 + s.cx + d.x() * (s.f + s.b1) + d.y() * s.b2,
                       s.H * 0.5 + s.cy + d.y() * s.f);
  return metashape - Vec2(0.5, 0.5);  // Metashape's top-left pixel centre is (0.5, 0.5)
}

MsChunk ms_chunk() {
  MsChunk c;
  c.sensors = {{"frame", 6000, 4000, 4812.5, 12.25, -30.5, 3.5, 1.25, -0.081, 0.093, -0.031, 0, 0.00042, -0.00071},
               {"fisheye", 2000, 1500, 900.0, -4.5, 6.25, 0.5, 0, 0.021, -0.007, 0.0012, -0.0003, 0, 0}};
  c.rotation = Eigen::AngleAxisd(0.4, Vec3(0.3, -1, 0.2).normalized()).toRotationMatrix();
  c.translation = Vec3(4321.5, -1234.25, 98.0);
  c.scale = 2.75;
  c.component = similarity(Eigen::AngleAxisd(-0.2, Vec3(1, 0, 0)).toRotationMatrix(), Vec3(1, 2, 3), 1.5);
  for (int i = 0; i < 4; ++i) {
    const auto pose = PinholeCamera::look_at({5 * std::cos(i), 5 * std::sin(i), 1.0 + i}, {0, 0, 0}, {0, 0, 1},
                                             1, 1, 0, 0, 1, 1);
    Eigen::Matrix4d to_chunk = Eigen::Matrix4d::Identity();
    to_chunk.topLeftCorner<3, 3>() = pose.R.transpose();
    to_chunk.topRightCorner<3, 1>() = pose.center();
    c.cameras.push_back({i % 2, "IMG_" + std::to_string(100 + i), to_chunk, i == 3 ? "0" : ""});
  }
  return c;
}

// ------------------------------------------------------------- OpenMVG / AliceVision

struct SfmCamera {
  std::string type;  // OpenMVG or AliceVision type name
  int W, H;
  double fx, fy, ppx, ppy;  // pixels, absolute principal point
  std::vector<double> dist;
  bool fisheye;
};

struct SfmView {
  int intrinsic;
  Mat3 R;  // world to camera
  Vec3 C;
  std::string file;
};

Vec2 sfm_project(const SfmCamera& c, const SfmView& v, const Vec3& X) {
  const Vec3 xc = v.R * (X - v.C);
  Vec2 n(xc.x() / xc.z(), xc.y() / xc.z()), d = n;
  const auto& k = c.dist;
  if (c.fisheye) {
    const double r = n.norm(), th = std::atan(r), t2 = th * th;
    const double thd = th * (1 + k[0] * t2 + k[1] * t2 * t2 + k[2] * t2 * t2 * t2 + k[3] * t2 * t2 * t2 * t2);
    d = r > 0 ? Vec2(n * (thd / r)) : n;
  } else if (k.size() == 1) {
    d = radial_tangential(n, k[0], 0, 0, 0, 0, 0);
  } else if (k.size() == 3) {
    d = radial_tangential(n, k[0], k[1], k[2], 0, 0, 0);
  } else if (k.size() == 5) {
    d = radial_tangential(n, k[0], k[1], k[2], 0, k[4], k[3]);  // t2 (r^2 + 2x^2) + 2 t1 x y
  }
  return {c.fx * d.x() + c.ppx, c.fy * d.y() + c.ppy};
}

std::vector<SfmView> sfm_views(int n, int intrinsics) {
  std::vector<SfmView> views;
  for (int i = 0; i < n; ++i) {
    const auto pose = PinholeCamera::look_at({4 * std::cos(0.7 * i), 4 * std::sin(0.7 * i), 0.5 * i},
                                             {0.1, 0, 0.2}, {0, 0, 1}, 1, 1, 0, 0, 1, 1);
    views.push_back({i % intrinsics, pose.R, pose.center(), "DSC_" + std::to_string(i) + ".JPG"});
  }
  return views;
}

std::string json_array(const std::vector<double>& v, bool strings) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + (strings ? "\"" + num(v[i]) + "\"" : num(v[i]));
  return s + "]";
}

}  // namespace

TEST(Metashape, ProjectsLikeMetashapeFrameFisheyeChunkAndComponent) {
  const MsChunk c = ms_chunk();
  const fs::path dir = test::temp_dir("metashape_projection");
  write(dir / "cameras.xml", ms_xml(c));
  write(dir / "photos" / "sub" / "IMG_101.JPG", "x");  // found by label, recursively
  const Scene scene = io::read_scene((dir / "cameras.xml").string());
  EXPECT_EQ(scene.format, "metashape");
  EXPECT_NE(scene.producer.find("Agisoft Metashape"), std::string::npos);
  EXPECT_EQ(scene.views[1].image_path, (dir / "photos" / "sub" / "IMG_101.JPG").string());
  bool unaligned = false, missing = false;
  for (const auto& w : scene.warnings) {
    unaligned |= w.find("1 cameras are not aligned") != std::string::npos;
    missing |= w.find("3 images not found") != std::string::npos;
  }
  EXPECT_TRUE(unaligned && missing);
  const ProjectFn expected = [&](std::size_t i, const Vec3& X) { return ms_project(c, c.cameras[i], X); };
  expect_projects_like(scene, expected, 4);
  expect_projects_like(json_round_trip(scene, "metashape_json"), expected, 4);
  EXPECT_EQ(scene.views[1].camera.lens, LensModel::Fisheye);
  EXPECT_NE(scene.views[0].camera.skew, 0.0);
}

// A georeferenced chunk's world frame is geocentric (its transform maps to
// ECEF); a local one places nothing on Earth.
TEST(Metashape, GeoreferencedChunkStatesItsCrs) {
  const fs::path dir = test::temp_dir("metashape_crs");
  MsChunk c = ms_chunk();
  const std::string wgs84 =
      "GEOGCS[\"WGS 84\",DATUM[\"World Geodetic System 1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,"
      "AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,"
      "AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.01745329251994328,AUTHORITY[\"EPSG\",\"9102\"]],"
      "AUTHORITY[\"EPSG\",\"4326\"]]";
  c.reference = wgs84;
  write(dir / "geo.xml", ms_xml(c));
  const Scene geo = io::read_metashape((dir / "geo.xml").string());
  EXPECT_EQ(geo.crs, wgs84);
  EXPECT_TRUE(geo.crs_geocentric);
  c.reference = "LOCAL_CS[\"Local Coordinates (m)\",LOCAL_DATUM[\"Local Datum\",0],UNIT[\"metre\",1]]";
  write(dir / "local.xml", ms_xml(c));
  const Scene local = io::read_metashape((dir / "local.xml").string());
  EXPECT_TRUE(local.crs.empty());
  c.reference.clear();
  write(dir / "none.xml", ms_xml(c));
  EXPECT_TRUE(io::read_metashape((dir / "none.xml").string()).crs.empty());
}

TEST(Metashape, BadInputIsOneLineError) {
  const fs::path dir = test::temp_dir("metashape_bad");
  MsChunk c = ms_chunk();
  c.cameras[2].sensor = 7;
  write(dir / "missing_sensor.xml", ms_xml(c));
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_metashape((dir / "missing_sensor.xml").string()),
                                "camera 2 ('IMG_102') refers to sensor 7, which the file does not define");
  c = ms_chunk();
  c.sensors[0].k4 = 0.001;
  write(dir / "k4.xml", ms_xml(c));
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_metashape((dir / "k4.xml").string()), "k4 (the r^8 term)");
  write(dir / "unaligned.xml", "<document><chunk><sensors/><cameras><camera id=\"0\" sensor_id=\"0\" "
                               "label=\"a\"/></cameras></chunk></document>");
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_metashape((dir / "unaligned.xml").string()), "no aligned camera");
  write(dir / "truncated.xml", ms_xml(ms_chunk()).substr(0, 700));
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_metashape((dir / "truncated.xml").string()), "malformed XML");
}

TEST(OpenMvg, ProjectsLikeOpenMvgWithStructure) {
  const std::vector<SfmCamera> cams = {
      {"pinhole_brown_t2", 3000, 2000, 2400.5, 2400.5, 1501.25, 998.75, {-0.11, 0.05, -0.01, 0.0012, -0.0009}, false},
      {"fisheye", 1600, 1200, 700.0, 700.0, 801.5, 597.0, {0.02, -0.006, 0.001, -0.0002}, true},
      {"pinhole_radial_k3", 3000, 2000, 2600, 2600, 1490, 1003, {-0.08, 0.02, 0.001}, false}};
  const auto views = sfm_views(5, 3);
  const fs::path dir = test::temp_dir("openmvg_projection");
  std::ostringstream j;
  j << "{\n \"sfm_data_version\": \"0.3\",\n \"root_path\": \"" << (dir / "nowhere").string() << "\",\n \"views\": [";
  for (std::size_t i = 0; i < views.size(); ++i) {
    const SfmCamera& c = cams[std::size_t(views[i].intrinsic)];
    j << (i ? "," : "") << "{\"key\": " << i << ", \"value\": {\"polymorphic_id\": 1073741824, \"ptr_wrapper\": {\"id\": "
      << 2147483649u + i << ", \"data\": {\"local_path\": \"\", \"filename\": \"" << views[i].file
      << "\", \"width\": " << c.W << ", \"height\": " << c.H << ", \"id_view\": " << i
      << ", \"id_intrinsic\": " << views[i].intrinsic << ", \"id_pose\": " << i << "}}}}";
  }
  j << "],\n \"intrinsics\": [";
  for (std::size_t i = 0; i < cams.size(); ++i) {
    const SfmCamera& c = cams[i];
    const char* key = c.type == "pinhole_brown_t2" ? "disto_t2" : c.type == "fisheye" ? "fisheye" : "disto_k3";
    j << (i ? "," : "") << "{\"key\": " << i << ", \"value\": {\"polymorphic_id\": " << 2147483649u + i
      << ", \"polymorphic_name\": \"" << c.type << "\", \"ptr_wrapper\": {\"id\": " << 2147483700u + i
      << ", \"data\": {\"width\": " << c.W << ", \"height\": " << c.H << ", \"focal_length\": " << num(c.fx)
      << ", \"principal_point\": " << json_array({c.ppx, c.ppy}, false) << ", \"" << key
      << "\": " << json_array(c.dist, false) << "}}}}";
  }
  j << "],\n \"extrinsics\": [";
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Mat3& R = views[i].R;
    j << (i ? "," : "") << "{\"key\": " << i << ", \"value\": {\"rotation\": [" << json_array({R(0, 0), R(0, 1), R(0, 2)}, false)
      << "," << json_array({R(1, 0), R(1, 1), R(1, 2)}, false) << "," << json_array({R(2, 0), R(2, 1), R(2, 2)}, false)
      << "], \"center\": " << json_array({views[i].C.x(), views[i].C.y(), views[i].C.z()}, false) << "}}";
  }
  // One point seen by every view, at its exact projection.
  const Vec3 X(0.1, 0.05, 0.2);
  j << "],\n \"structure\": [{\"key\": 0, \"value\": {\"X\": " << json_array({X.x(), X.y(), X.z()}, false) << ", \"observations\": [";
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Vec2 x = sfm_project(cams[std::size_t(views[i].intrinsic)], views[i], X);
    j << (i ? "," : "") << "{\"key\": " << i << ", \"value\": {\"id_feat\": 3, \"x\": " << json_array({x.x(), x.y()}, false) << "}}";
  }
  j << "]}}],\n \"control_points\": []\n}\n";
  write(dir / "sfm_data.json", j.str());
  const Scene scene = io::read_scene((dir / "sfm_data.json").string());
  EXPECT_EQ(scene.format, "openmvg");
  const ProjectFn expected = [&](std::size_t i, const Vec3& P) {
    return sfm_project(cams[std::size_t(views[i].intrinsic)], views[i], P);
  };
  expect_projects_like(scene, expected, views.size());
  expect_projects_like(json_round_trip(scene, "openmvg_json"), expected, views.size());
  const ReprojectionStats r = reprojection_error(scene);
  EXPECT_EQ(r.observations, views.size());
  EXPECT_LT(r.max, 1e-6);
}

namespace {

std::string alicevision_json(const std::vector<SfmCamera>& cams, const std::vector<SfmView>& views,
                             const std::string& version) {
  const bool offset_pp = version >= "1.2.1", mm = version >= "1.2.2", ratio_times = version >= "1.2.5";
  std::ostringstream j;
  j << "{\n \"version\": [\"" << version[0] << "\", \"" << version[2] << "\", \"" << version[4] << "\"],\n"
    << " \"featuresFolders\": [\"\"],\n \"views\": [";
  for (std::size_t i = 0; i < views.size(); ++i)
    j << (i ? "," : "") << "{\"viewId\": \"" << 1000 + i << "\", \"poseId\": \"" << 1000 + i
      << "\", \"intrinsicId\": \"" << 77 + views[i].intrinsic << "\", \"path\": \"C:\\\\Users\\\\me\\\\shoot\\\\"
      << views[i].file << "\", \"width\": \"" << cams[std::size_t(views[i].intrinsic)].W << "\"}";
  j << "],\n \"intrinsics\": [";
  for (std::size_t i = 0; i < cams.size(); ++i) {
    const SfmCamera& c = cams[i];
    const double sensor = 36.0;
    j << (i ? "," : "") << "{\"intrinsicId\": \"" << 77 + i << "\", \"width\": \"" << c.W << "\", \"height\": \""
      << c.H << "\", \"type\": \"" << c.type << "\", \"sensorWidth\": \"" << sensor << "\", ";
    if (mm)
      j << "\"focalLength\": \"" << num(c.fx * sensor / c.W) << "\", \"pixelRatio\": \""
        << num(ratio_times ? c.fy / c.fx : c.fx / c.fy) << "\", ";
    else
      j << "\"pxFocalLength\": \"" << num(c.fx) << "\", ";
    j << "\"principalPoint\": " << json_array({c.ppx - (offset_pp ? c.W / 2.0 : 0), c.ppy - (offset_pp ? c.H / 2.0 : 0)}, true)
      << ", \"distortionParams\": " << json_array(c.dist, true) << ", \"locked\": \"0\"}";
  }
  j << "],\n \"poses\": [";
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Mat3& R = views[i].R;  // written column by column (Eigen's storage order)
    j << (i ? "," : "") << "{\"poseId\": \"" << 1000 + i << "\", \"pose\": {\"transform\": {\"rotation\": "
      << json_array({R(0, 0), R(1, 0), R(2, 0), R(0, 1), R(1, 1), R(2, 1), R(0, 2), R(1, 2), R(2, 2)}, true)
      << ", \"center\": " << json_array({views[i].C.x(), views[i].C.y(), views[i].C.z()}, true)
      << "}, \"locked\": \"0\"}}";
  }
  j << "]\n}\n";
  return j.str();
}

}  // namespace

TEST(AliceVision, ProjectsLikeAliceVisionAcrossFileVersions) {
  const std::vector<SfmCamera> cams_old = {
      {"brown", 3000, 2000, 2400.5, 2400.5, 1501.25, 998.75, {-0.11, 0.05, -0.01, 0.0012, -0.0009}, false},
      {"radial3", 3000, 2000, 2600, 2600, 1490, 1003, {-0.08, 0.02, 0.001}, false}};
  const std::vector<SfmCamera> cams_new = {
      {"fisheye4", 1600, 1200, 700.0, 707.0, 801.5, 597.0, {0.02, -0.006, 0.001, -0.0002}, true},
      {"radial1", 3000, 2000, 2600, 2590, 1490, 1003, {-0.08}, false}};
  const auto views = sfm_views(4, 2);
  for (const auto& [version, cams] : {std::make_pair(std::string("1.0.0"), cams_old),
                                      std::make_pair(std::string("1.2.3"), cams_new),
                                      std::make_pair(std::string("1.2.5"), cams_new)}) {
    SCOPED_TRACE(version);
    const fs::path dir = test::temp_dir("alicevision_" + version);
    write(dir / "cameras.sfm", alicevision_json(cams, views, version));
    write(dir / "moved" / "DSC_2.JPG", "x");
    io::SceneReadOptions options;
    options.image_dir = (dir / "moved").string();
    const Scene scene = io::read_scene((dir / "cameras.sfm").string(), options);
    EXPECT_EQ(scene.format, "alicevision");
    EXPECT_EQ(scene.views[2].image_path, (dir / "moved" / "DSC_2.JPG").string());  // Windows path, found by name
    const ProjectFn expected = [&](std::size_t i, const Vec3& P) {
      return sfm_project(cams[std::size_t(views[i].intrinsic)], views[i], P);
    };
    expect_projects_like(scene, expected, views.size());
    expect_projects_like(json_round_trip(scene, "alicevision_json_" + version), expected, views.size());
  }
}

TEST(AliceVision, UnsupportedTypeAndRigAreErrors) {
  const fs::path dir = test::temp_dir("alicevision_bad");
  std::vector<SfmCamera> cams = {{"equidistant_r3", 100, 100, 50, 50, 50, 50, {0, 0, 0}, false}};
  write(dir / "type.sfm", alicevision_json(cams, sfm_views(1, 1), "1.0.0"));
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_alicevision((dir / "type.sfm").string()),
                                "intrinsic type 'equidistant_r3' is not supported");
  cams[0].type = "pinhole";
  cams[0].dist = {};
  std::string rig = alicevision_json(cams, sfm_views(1, 1), "1.0.0");
  rig.replace(rig.find("\"viewId\""), 0, "\"rigId\": \"1\", \"subPoseId\": \"0\", ");
  write(dir / "rig.sfm", rig);
  MESHNBV_EXPECT_ERROR_CONTAINS(io::read_alicevision((dir / "rig.sfm").string()), "camera rig");
}
