// Georeferencing a scene (docs/missions.md): a similarity from the scene
// frame to a projected CRS (metres east, north, up), and the conversions to
// and from WGS84 through PROJ (Debian libproj-dev; proj_create_crs_to_crs,
// never by hand).
//
// Sources:
//  - a file (`--georef FILE`): {"crs": "EPSG:32632", "transform": [16
//    numbers, row-major 4x4, scene -> CRS]}; the CRS's vertical axis is the
//    ellipsoidal height unless the CRS says otherwise (a compound CRS with a
//    vertical datum, e.g. "EPSG:32632+5773");
//  - the photos' EXIF GPS: a similarity fitted by Umeyama (least squares,
//    scale included) from the camera centres to the GPS positions expressed
//    in the local east-north-up frame of the UTM zone of their centroid,
//    with per-photo residuals.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshnbv/scene.h"

namespace meshnbv::mission {

using Mat4 = Eigen::Matrix4d;

struct Geodetic {
  double latitude = 0, longitude = 0;  // WGS84 degrees
  double height = 0;                   // ellipsoidal metres (EPSG:4979)
};

struct GpsFix {
  std::string label;     // the view's
  Vec3 scene;            // its camera centre
  Geodetic gps;          // its EXIF position (altitude taken as ellipsoidal)
};

struct Georeference {
  std::string crs;                      // anything PROJ reads: "EPSG:32632", WKT, PROJJSON
  Mat4 scene_to_crs = Mat4::Identity();
  std::string source;                   // where it came from, for reports
  // EXIF fits: the photos used and the distance (metres) between each GPS
  // position and the fitted camera centre.
  std::vector<std::string> fit_labels;
  std::vector<double> residuals;
  double rms_residual() const;
};

// The JSON of a --georef file; Error (one line, naming the file) for a
// missing key, a transform that is not 16 finite numbers or not an affine
// similarity (GeoFrame), or a CRS PROJ does not know.
Georeference parse_georef_json(const std::string& text, const std::string& name);
Georeference read_georef_file(const std::string& path);
std::string georef_json(const Georeference& georef);

// The EXIF GPS of every view with an image file (views without GPS are
// skipped; unreadable EXIF is an Error).
std::vector<GpsFix> gps_fixes(const Scene& scene);
// Fewer than 3 fixes, or fixes that do not span a plane (collinear or
// coincident, in the scene or on the ground) are an Error.
Georeference fit_georef(const std::vector<GpsFix>& fixes);

// The conversions of one georeference (not thread-safe: one per thread).
class GeoFrame {
 public:
  explicit GeoFrame(const Georeference& georef);
  ~GeoFrame();
  GeoFrame(const GeoFrame&) = delete;
  GeoFrame& operator=(const GeoFrame&) = delete;

  const Georeference& georef() const;
  Vec3 to_crs(const Vec3& scene) const;
  Vec3 from_crs(const Vec3& crs) const;
  Geodetic to_wgs84(const Vec3& scene) const;
  Vec3 from_wgs84(const Geodetic& g) const;
  Vec3 crs_from_wgs84(const Geodetic& g) const;
  // Height above mean sea level (EGM96, PROJ's egm96_15 grid) of a WGS84
  // position, and back; for KML, whose absolute altitudes are above sea level.
  double egm96_height(const Geodetic& g) const;
  double ellipsoidal_from_egm96(double latitude, double longitude, double egm96) const;

  // The scene direction of the CRS's vertical axis (unit), metres per scene
  // unit, and the height (metres along that axis) of a scene point.
  const Vec3& up() const;
  double metres_per_unit() const;
  double crs_height(const Vec3& scene) const;
  // Heading (degrees clockwise from true north, [0, 360)) of the horizontal
  // part of scene direction `dir` at scene point `at`; pitch (degrees, -90 =
  // straight down) of `dir`.
  double heading(const Vec3& at, const Vec3& dir) const;
  double pitch(const Vec3& dir) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshnbv::mission
