// Georeferencing (meshnbv::mission, georef.h) and the EXIF reader (io/exif.h).
// Round trips scene -> WGS84 -> scene must hold to 1 cm; the EXIF fit must
// recover a known similarity to the noise put on the synthetic GPS tags.
#include <cmath>
#include <fstream>
#include <random>

#include <Eigen/Geometry>

#include <exiv2/exiv2.hpp>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/exif.h"
#include "meshnbv/mission/georef.h"
#include "test_geometry.h"
#include "test_util.h"

namespace meshnbv::test {
namespace {

using mission::GeoFrame;
using mission::Georeference;

Georeference random_georef(std::mt19937& rng, const char* crs = "EPSG:32632") {
  std::uniform_real_distribution<double> u(0, 1);
  Georeference g;
  g.crs = crs;
  const double s = 0.2 + 3 * u(rng);
  g.scene_to_crs.topLeftCorner<3, 3>() = s * random_rotation(rng);
  g.scene_to_crs.topRightCorner<3, 1>() = Vec3(450000 + 100000 * u(rng), 5000000 + 100000 * u(rng), 50 + 500 * u(rng));
  return g;
}

TEST(MissionGeoref, RoundTripSceneWgs84SceneWithinOneCentimetre) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-300, 300);
  for (const char* crs : {"EPSG:32632", "EPSG:32733", "EPSG:2056"}) {
    const Georeference g = random_georef(rng, crs);
    if (std::string(crs) == "EPSG:2056") {  // Swiss LV95: other false easting/northing
      mission::Mat4 m = g.scene_to_crs;
      m.topRightCorner<3, 1>() = Vec3(2600000, 1200000, 500);
      Georeference h = g;
      h.scene_to_crs = m;
      const GeoFrame f(h);
      for (int i = 0; i < 50; ++i) {
        const Vec3 p(u(rng), u(rng), u(rng));
        EXPECT_LT((f.from_wgs84(f.to_wgs84(p)) - p).norm() * f.metres_per_unit(), 0.01) << crs;
      }
      continue;
    }
    const GeoFrame f(g);
    for (int i = 0; i < 50; ++i) {
      const Vec3 p(u(rng), u(rng), u(rng));
      const mission::Geodetic geo = f.to_wgs84(p);
      EXPECT_LT((f.from_wgs84(geo) - p).norm() * f.metres_per_unit(), 0.01) << crs;
      // EGM96 heights (KML) back to ellipsoidal.
      EXPECT_NEAR(f.ellipsoidal_from_egm96(geo.latitude, geo.longitude, f.egm96_height(geo)), geo.height, 0.01);
    }
  }
}

TEST(MissionGeoref, KnownPointOfUtm32) {
  // The central meridian of zone 32 (9 E) at the false easting: latitude of
  // northing 5,000,000 m is about 45.1 degrees N.
  Georeference g;
  g.crs = "EPSG:32632";
  g.scene_to_crs.topRightCorner<3, 1>() = Vec3(500000, 5000000, 100);
  const GeoFrame f(g);
  const mission::Geodetic geo = f.to_wgs84(Vec3::Zero());
  EXPECT_NEAR(geo.longitude, 9.0, 1e-9);
  EXPECT_NEAR(geo.latitude, 45.1536, 1e-3);
  EXPECT_NEAR(geo.height, 100.0, 1e-6);  // ellipsoidal height axis: passed through
  EXPECT_NEAR(f.pitch(Vec3(0, 0, -1)), -90.0, 1e-9);
  EXPECT_NEAR(f.heading(Vec3::Zero(), Vec3(0, 1, 0)), 0.0, 1e-6);  // grid north = true north on 9 E
  EXPECT_NEAR(f.heading(Vec3::Zero(), Vec3(1, 0, -1)), 90.0, 1e-6);
}

TEST(MissionGeoref, FileParsingAndErrors) {
  const Georeference g = mission::parse_georef_json(
      R"({"crs": "EPSG:32632", "transform": [2,0,0,500000, 0,2,0,5000000, 0,0,2,10, 0,0,0,1]})", "g.json");
  EXPECT_EQ(g.crs, "EPSG:32632");
  EXPECT_EQ(g.scene_to_crs(0, 3), 500000);
  EXPECT_DOUBLE_EQ(GeoFrame(g).metres_per_unit(), 2.0);
  const Georeference back = mission::parse_georef_json(mission::georef_json(g), "back.json");
  EXPECT_EQ(back.scene_to_crs, g.scene_to_crs);
  auto fails = [](const std::string& text, const std::string& fragment) {
    try {
      mission::parse_georef_json(text, "g.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  fails(R"({"transform": []})", "\"crs\"");
  fails(R"({"crs": "EPSG:32632", "transform": [1,2,3]})", "16 numbers");
  fails(R"({"crs": "EPSG:32632", "transform": [1,0,0,0, 0,2,0,0, 0,0,1,0, 0,0,0,1]})", "similarity");
  fails(R"({"crs": "EPSG:32632", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 1,0,0,1]})", "last row");
  fails(R"({"crs": "EPSG:999999", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})", "unknown CRS");
  fails(R"({"crs": "EPSG:4326", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})", "projected");
  fails("{", "not valid JSON");
}

TEST(MissionGeoref, ExifFitRecoversTheSimilarityToTheGpsNoise) {
  std::mt19937 rng(11);
  const Georeference truth = random_georef(rng);
  const GeoFrame f(truth);
  std::normal_distribution<double> noise(0.0, 0.3);  // metres, on each GPS coordinate
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<mission::GpsFix> fixes;
  const double s = f.metres_per_unit();
  for (int i = 0; i < 40; ++i) {
    // Camera centres on a ring 40 m across, 10 to 20 m up.
    const double a = 2 * M_PI * i / 40;
    const Vec3 crs = f.to_crs(Vec3::Zero()) + Vec3(20 * std::cos(a), 20 * std::sin(a), 15 + 5 * u(rng));
    const Vec3 scene = f.from_crs(crs);
    const Vec3 noisy = crs + Vec3(noise(rng), noise(rng), noise(rng));
    fixes.push_back({"v" + std::to_string(i), scene, f.to_wgs84(f.from_crs(noisy))});
  }
  const Georeference fit = mission::fit_georef(fixes);
  const GeoFrame g(fit);
  // RMS residual close to the noise (3 coordinates of sigma 0.3 m: ~0.52 m).
  EXPECT_NEAR(fit.rms_residual(), 0.3 * std::sqrt(3.0), 0.15);
  // Positions near the ring agree to a fraction of the noise.
  for (int i = 0; i < 20; ++i) {
    const Vec3 p = Vec3(u(rng), u(rng), u(rng)) * 20 / s;
    const mission::Geodetic a = f.to_wgs84(p), b = g.to_wgs84(p);
    EXPECT_LT((f.from_wgs84(b) - p).norm() * s, 0.3) << "fit off by more than the noise";
    EXPECT_NEAR(a.height, b.height, 0.3);
  }
  EXPECT_NEAR(g.metres_per_unit(), s, 0.01 * s);
}

TEST(MissionGeoref, ExifFitNeedsThreeWellSpreadPhotos) {
  std::vector<mission::GpsFix> fixes = {{"a", Vec3(0, 0, 0), {45, 9, 100}},
                                        {"b", Vec3(10, 0, 0), {45.0001, 9, 100}}};
  try {
    mission::fit_georef(fixes);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at least 3 photos with GPS, found 2"), std::string::npos) << e.what();
  }
  fixes.push_back({"c", Vec3(20, 0, 0), {45.0002, 9, 100}});  // on a line
  try {
    mission::fit_georef(fixes);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("in a line"), std::string::npos) << e.what();
  }
}

// Geodesy written out (WGS84 ellipsoid), independent of PROJ: geodetic
// (degrees, metres) to geocentric, and the east-north-up axes at a point.
Vec3 ecef_of(double lat_deg, double lon_deg, double h) {
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double lat = lat_deg * M_PI / 180, lon = lon_deg * M_PI / 180;
  const double n = a / std::sqrt(1 - e2 * std::sin(lat) * std::sin(lat));
  return Vec3((n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon),
              (n * (1 - e2) + h) * std::sin(lat));
}
Mat3 enu_axes(double lat_deg, double lon_deg) {  // columns: east, north, up in ECEF
  const double lat = lat_deg * M_PI / 180, lon = lon_deg * M_PI / 180;
  Mat3 m;
  m.col(0) = Vec3(-std::sin(lon), std::cos(lon), 0);
  m.col(1) = Vec3(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  m.col(2) = Vec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  return m;
}

// Geodetic positions over a square `size` metres across around (lat, lon),
// 0 to 60 m up.
std::vector<mission::Geodetic> site(double lat, double lon, double h, double size, int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5), up(0, 60);
  std::vector<mission::Geodetic> out;
  for (int i = 0; i < n; ++i)
    out.push_back({lat + u(rng) * size / 111132.0, lon + u(rng) * size / (111320.0 * std::cos(lat * M_PI / 180)),
                   h + up(rng)});
  return out;
}

// (d^2 + 2 d h) / R for a square site `size` metres across (d its
// half-diagonal) and 60 m high: the sag of the ground below a plane and the
// convergence of the verticals over the height (R the Earth's radius).
double curvature_bound(double size) {
  const double d = size / std::sqrt(2.0), h = 60;
  return (d * d + 2 * d * h) / 6371000.0;
}

double metres_between(const mission::Geodetic& a, const mission::Geodetic& b) {
  const double dn = (a.latitude - b.latitude) * M_PI / 180 * 6371000;
  const double de = (a.longitude - b.longitude) * M_PI / 180 * 6371000 * std::cos(a.latitude * M_PI / 180);
  return std::sqrt(dn * dn + de * de + (a.height - b.height) * (a.height - b.height));
}

// A scene in geocentric coordinates (a COLMAP model aligned to ECEF, here
// also scaled and turned by a similarity): localized to UTM and every
// point's WGS84 position within 1 cm of the truth over a 500 m site.
TEST(MissionGeoref, GeocentricSceneWithinOneCentimetre) {
  const auto truth = site(46.5, 7.25, 480, 500, 300);
  Georeference g = mission::parse_georef_argument("ecef");
  EXPECT_TRUE(mission::is_curved_frame(g));
  // scene = S^-1 (ecef): scene units of 0.5 m, turned.
  mission::Mat4 s = mission::Mat4::Identity();
  s.topLeftCorner<3, 3>() = 0.5 * Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  s.topRightCorner<3, 1>() = ecef_of(46.5, 7.25, 480);
  g.scene_to_crs = s;
  std::vector<Vec3> scene;
  for (const auto& t : truth) scene.push_back((s.inverse() * ecef_of(t.latitude, t.longitude, t.height).homogeneous()).head<3>());
  const Georeference local = mission::localize_georef(g, scene);
  EXPECT_EQ(local.crs, "EPSG:32632");
  EXPECT_NE(local.source.find("largest deviation"), std::string::npos);
  // No similarity follows the Earth's curvature: the deviation is of the
  // order d^2 / R (d: the site's half-diagonal), and what is reported holds.
  EXPECT_LT(local.deviation_m, curvature_bound(500));
  const GeoFrame f(local);
  EXPECT_NEAR(f.metres_per_unit(), 0.5, 0.5 * 1e-3);  // UTM's scale factor is within 1e-3 of 1
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_LT(metres_between(f.to_wgs84(scene[i]), truth[i]), local.deviation_m + 1e-3) << i;
    EXPECT_LT((f.from_wgs84(f.to_wgs84(scene[i])) - scene[i]).norm() * f.metres_per_unit(), 0.01);
  }
  // Over a 100 m site (a building), within 1 cm.
  const auto small = site(46.5, 7.25, 480, 100, 100);
  std::vector<Vec3> small_scene;
  for (const auto& t : small) small_scene.push_back((s.inverse() * ecef_of(t.latitude, t.longitude, t.height).homogeneous()).head<3>());
  const GeoFrame fs(mission::localize_georef(g, small_scene));
  for (std::size_t i = 0; i < small.size(); ++i) EXPECT_LT(metres_between(fs.to_wgs84(small_scene[i]), small[i]), 0.01) << i;
  // The vertical of the localized frame is the local vertical.
  const Vec3 up_ecef = enu_axes(46.5, 7.25).col(2);
  EXPECT_GT((s.topLeftCorner<3, 3>() * f.up()).normalized().dot(up_ecef), std::cos(0.01 * M_PI / 180));
}

// COLMAP's --alignment_type enu: a tangent frame at the first photo.
TEST(MissionGeoref, EnuSceneWithinOneCentimetre) {
  const auto truth = site(-33.86, 151.2, 20, 800, 300);
  const Georeference g = mission::parse_georef_argument("enu:-33.86,151.2,20");
  ASSERT_TRUE(g.enu_origin.has_value());
  const Vec3 o = ecef_of(-33.86, 151.2, 20);
  const Mat3 axes = enu_axes(-33.86, 151.2);
  std::vector<Vec3> scene;
  for (const auto& t : truth) scene.push_back(axes.transpose() * (ecef_of(t.latitude, t.longitude, t.height) - o));
  const Georeference local = mission::localize_georef(g, scene);
  EXPECT_EQ(local.crs, "EPSG:32756");
  EXPECT_LT(local.deviation_m, curvature_bound(800));
  const GeoFrame f(local);
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_LT(metres_between(f.to_wgs84(scene[i]), truth[i]), local.deviation_m + 1e-3) << i;
  // The same through a file.
  const Georeference file = mission::parse_georef_json(
      R"({"crs": "ENU", "origin": [-33.86, 151.2, 20], "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})", "enu.json");
  const GeoFrame ff(mission::localize_georef(file, scene));
  EXPECT_LT(metres_between(ff.to_wgs84(scene[0]), truth[0]), local.deviation_m + 1e-3);
}

// A Metashape chunk's world frame: geocentric of the chunk CRS's datum.
TEST(MissionGeoref, SceneCrsOfAGeoreferencedChunk) {
  Scene scene;
  scene.crs = "EPSG:4326";
  scene.crs_geocentric = true;
  const auto g = mission::scene_crs_georef(scene);
  ASSERT_TRUE(g.has_value());
  EXPECT_TRUE(mission::is_curved_frame(*g));
  const auto truth = site(52.37, 4.89, 0, 300, 100);
  std::vector<Vec3> points;
  for (const auto& t : truth) points.push_back(ecef_of(t.latitude, t.longitude, t.height));
  const Georeference local = mission::localize_georef(*g, points);
  const GeoFrame f(local);
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_LT(metres_between(f.to_wgs84(points[i]), truth[i]), local.deviation_m + 1e-3) << i;
  EXPECT_LT(local.deviation_m, curvature_bound(300));
  scene.crs = "EPSG:32631";  // a scene whose coordinates are in UTM 31 itself
  scene.crs_geocentric = false;
  EXPECT_EQ(mission::scene_crs_georef(scene)->crs, "EPSG:32631");
  scene.crs.clear();
  EXPECT_FALSE(mission::scene_crs_georef(scene).has_value());
}

TEST(MissionGeoref, CurvedFrameErrors) {
  // 60 km across: far more than 1 m between any similarity and the Earth.
  const auto wide = site(45, 9, 100, 60000, 200);
  std::vector<Vec3> points;
  for (const auto& t : wide) points.push_back(ecef_of(t.latitude, t.longitude, t.height));
  MESHNBV_EXPECT_ERROR_CONTAINS(mission::localize_georef(mission::parse_georef_argument("ecef"), points),
                                "too much of the Earth's curvature");
  MESHNBV_EXPECT_ERROR_CONTAINS(mission::parse_georef_argument("enu:45,9"), "takes LAT,LON,H");
  MESHNBV_EXPECT_ERROR_CONTAINS(mission::parse_georef_argument("enu:45,190,0"), "the ENU origin must be");
  MESHNBV_EXPECT_ERROR_CONTAINS(
      mission::parse_georef_json(R"({"crs": "ENU", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})", "e.json"),
      "needs \"origin\"");
  MESHNBV_EXPECT_ERROR_CONTAINS(mission::localize_georef(mission::parse_georef_argument("ecef"), {Vec3::Zero()}),
                                "at least 3");
  // A geocentric file is accepted; a geographic one still is not.
  EXPECT_NO_THROW(mission::parse_georef_json(
      R"({"crs": "EPSG:4978", "transform": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})", "ecef.json"));
  MESHNBV_EXPECT_ERROR_CONTAINS(mission::GeoFrame(mission::parse_georef_argument("ecef")), "projected");
}

// A small JPEG written by OpenCV, tagged by exiv2 itself.
std::string tagged_jpeg(const std::string& dir, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& tags) {
  const std::string path = dir + "/" + name;
  cv::imwrite(path, cv::Mat(24, 32, CV_8UC3, cv::Scalar(90, 120, 150)));
  auto image = Exiv2::ImageFactory::open(path);
  image->readMetadata();
  Exiv2::ExifData& exif = image->exifData();
  for (const auto& [key, value] : tags) exif[key] = value;
  image->writeMetadata();
  return path;
}

TEST(ExifReader, GpsAndFocalLengthWrittenByExiv2) {
  const std::string dir = temp_dir("exif");
  const std::string path = tagged_jpeg(dir, "gps.jpg", {
      {"Exif.GPSInfo.GPSLatitudeRef", "S"}, {"Exif.GPSInfo.GPSLatitude", "33/1 51/1 3150/100"},
      {"Exif.GPSInfo.GPSLongitudeRef", "E"}, {"Exif.GPSInfo.GPSLongitude", "151/1 12/1 3600/100"},
      {"Exif.GPSInfo.GPSAltitude", "12345/100"}, {"Exif.Photo.FocalLength", "88/10"}});
  {
    auto image = Exiv2::ImageFactory::open(path);
    image->readMetadata();
    image->exifData()["Exif.GPSInfo.GPSAltitudeRef"] = uint8_t(0);
    image->exifData()["Exif.Photo.FocalLengthIn35mmFilm"] = uint16_t(24);
    image->writeMetadata();
  }
  const io::ExifInfo e = io::read_exif(path);
  ASSERT_TRUE(e.has_gps());
  EXPECT_NEAR(*e.latitude, -(33 + 51 / 60.0 + 31.5 / 3600.0), 1e-12);
  EXPECT_NEAR(*e.longitude, 151 + 12 / 60.0 + 36 / 3600.0, 1e-12);
  EXPECT_NEAR(*e.altitude, 123.45, 1e-12);
  EXPECT_NEAR(*e.focal_length_mm, 8.8, 1e-12);
  EXPECT_NEAR(*e.focal_length_35mm, 24, 0);
}

TEST(ExifReader, AbsentAndMalformedTags) {
  const std::string dir = temp_dir("exif_bad");
  const io::ExifInfo none = io::read_exif(tagged_jpeg(dir, "none.jpg", {{"Exif.Image.Make", "X"}}));
  EXPECT_FALSE(none.has_gps());
  EXPECT_FALSE(none.focal_length_mm.has_value());
  auto fails = [&](const std::string& name, const std::vector<std::pair<std::string, std::string>>& tags,
                   const std::string& fragment) {
    const std::string path = tagged_jpeg(dir, name, tags);
    try {
      io::read_exif(path);
      ADD_FAILURE() << name;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  fails("zero.jpg", {{"Exif.GPSInfo.GPSLatitudeRef", "N"}, {"Exif.GPSInfo.GPSLatitude", "45/0 0/1 0/1"},
                     {"Exif.GPSInfo.GPSLongitudeRef", "E"}, {"Exif.GPSInfo.GPSLongitude", "9/1 0/1 0/1"}},
        "zero denominator");
  fails("beyond.jpg", {{"Exif.GPSInfo.GPSLatitudeRef", "N"}, {"Exif.GPSInfo.GPSLatitude", "95/1 0/1 0/1"}},
        "beyond 90");
  fails("ref.jpg", {{"Exif.GPSInfo.GPSLatitudeRef", "Q"}, {"Exif.GPSInfo.GPSLatitude", "45/1 0/1 0/1"}},
        "GPSLatitudeRef");
  std::ofstream(dir + "/junk.jpg") << "not an image";
  EXPECT_THROW(io::read_exif(dir + "/junk.jpg"), Error);
  EXPECT_THROW(io::read_exif(dir + "/missing.jpg"), Error);
  // A format with no EXIF (PGM) is no GPS where a scene's photos are
  // searched for it, an error where EXIF is asked for; missing is an error.
  cv::imwrite(dir + "/grey.pgm", cv::Mat(8, 8, CV_8UC1, cv::Scalar(7)));
  EXPECT_FALSE(io::read_exif_if_known_type(dir + "/grey.pgm").has_value());
  EXPECT_THROW(io::read_exif(dir + "/grey.pgm"), Error);
  EXPECT_THROW(io::read_exif_if_known_type(dir + "/missing.jpg"), Error);
  const auto jpeg = io::read_exif_if_known_type(dir + "/none.jpg");
  ASSERT_TRUE(jpeg.has_value());
  EXPECT_FALSE(jpeg->has_gps());
}

}  // namespace
}  // namespace meshnbv::test
