// Georeferencing (meshnbv::mission, georef.h) and the EXIF reader (io/exif.h).
// Round trips scene -> WGS84 -> scene must hold to 1 cm; the EXIF fit must
// recover a known similarity to the noise put on the synthetic GPS tags.
#include <cmath>
#include <fstream>
#include <random>

#include <exiv2/exiv2.hpp>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/exif.h"
#include "meshnbv/mission/georef.h"
#include "test_util.h"

namespace meshnbv::test {
namespace {

using mission::GeoFrame;
using mission::Georeference;

Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

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
}

}  // namespace
}  // namespace meshnbv::test
