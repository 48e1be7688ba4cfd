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
//    with per-photo residuals;
//  - a scene whose coordinates are geocentric (ECEF: a COLMAP model aligned
//    with `model_aligner --alignment_type ecef`, a georeferenced Metashape
//    chunk's world frame) or a local east-north-up tangent frame (COLMAP's
//    `--alignment_type enu`): `--georef ecef`, `--georef enu:LAT,LON,H`, a
//    file whose "crs" is geocentric or "ENU" (with "origin"), or the
//    scene's own CRS (Scene::crs). Such a frame is curved against any map
//    projection; localize_georef expresses it as the similarity to the UTM
//    zone of the scene that fits it best over the scene's points, and
//    states the largest deviation.
#pragma once

#include <memory>
#include <optional>
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
  // Anything PROJ reads: "EPSG:32632", WKT, PROJJSON; a projected or
  // compound CRS for GeoFrame. Before localize_georef also a geocentric CRS
  // ("EPSG:4978") or "ENU" (a tangent frame at enu_origin).
  std::string crs;
  Mat4 scene_to_crs = Mat4::Identity();
  std::optional<Geodetic> enu_origin;   // crs == "ENU"
  std::string source;                   // where it came from, for reports
  // localize_georef of a geocentric or ENU frame: the largest distance
  // (metres), over the scene's points, between the fitted similarity and
  // the exact conversion; 0 otherwise.
  double deviation_m = 0;
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
// The argument of --georef: "ecef" (scene coordinates are WGS84 geocentric,
// EPSG:4978), "enu:LAT,LON,H" (a tangent frame with its origin at that
// WGS84 position, x east, y north, z up) or a file.
Georeference parse_georef_argument(const std::string& argument);
std::string georef_json(const Georeference& georef);

// Whether the georeference needs localize_georef (geocentric or ENU).
bool is_curved_frame(const Georeference& georef);
// A geocentric or ENU georeference as the similarity to the UTM zone of
// the points' centre, fitted (Umeyama) to the exact PROJ conversion of
// `scene_points` (a sample of the mesh and the camera centres); others
// are returned as they are. Error when the points are fewer than 3 or
// degenerate, or the deviation exceeds kMaxDeviation (a scene spanning
// too much of the Earth's curvature for one similarity).
constexpr double kMaxDeviation = 1.0;  // metres
Georeference localize_georef(const Georeference& georef, const std::vector<Vec3>& scene_points);
// The georeference a scene's source states (Scene::crs): geocentric of the
// CRS's datum when Scene::crs_geocentric, else that CRS; none when empty.
std::optional<Georeference> scene_crs_georef(const Scene& scene);

// The EXIF GPS of every view with an image file (views without GPS, and
// files of a type that holds no EXIF, such as PGM, are skipped; a missing
// file or malformed tags are an Error).
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
