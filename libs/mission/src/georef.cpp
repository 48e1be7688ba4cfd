// Georeferences and their conversions through PROJ (georef.h).
#include "meshnbv/mission/georef.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <geodesic.h>
#include <nlohmann/json.hpp>
#include <proj.h>
#include <proj_experimental.h>

#include "meshnbv/error.h"
#include "meshnbv/io/exif.h"
#include "meshnbv/io/file_util.h"
#include "coordinates_text.h"

namespace meshnbv::mission {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct ContextDeleter {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};
using Context = std::unique_ptr<PJ_CONTEXT, ContextDeleter>;
using Pj = std::unique_ptr<PJ, PjDeleter>;

std::string proj_error(PJ_CONTEXT* ctx) {
  const char* e = proj_context_errno_string(ctx, proj_context_errno(ctx));
  return e ? e : "unknown PROJ error";
}

// source -> target, longitude/latitude order for geographic CRSs.
Pj transformation(PJ_CONTEXT* ctx, PJ* source, PJ* target, const std::string& what) {
  Pj op(proj_create_crs_to_crs_from_pj(ctx, source, target, nullptr, nullptr));
  if (!op) throw Error("no coordinate operation " + what + ": " + proj_error(ctx));
  Pj norm(proj_normalize_for_visualization(ctx, op.get()));
  if (!norm) throw Error("no coordinate operation " + what + ": " + proj_error(ctx));
  return norm;
}

Vec3 run(PJ* op, PJ_DIRECTION dir, const Vec3& in, const char* what) {
  PJ_COORD c = proj_coord(in.x(), in.y(), in.z(), 0);
  c = proj_trans(op, dir, c);
  const Vec3 out(c.xyz.x, c.xyz.y, c.xyz.z);
  if (!out.allFinite())
    throw Error(std::string("coordinate conversion failed (") + what + ")");
  return out;
}

// The CRS with an ellipsoidal height axis when it has no vertical one.
Pj crs_3d(PJ_CONTEXT* ctx, const std::string& crs) {
  Pj pj(proj_create(ctx, crs.c_str()));
  if (!pj) throw Error("unknown CRS '" + crs + "': " + proj_error(ctx));
  const PJ_TYPE type = proj_get_type(pj.get());
  if (type != PJ_TYPE_PROJECTED_CRS && type != PJ_TYPE_COMPOUND_CRS)
    throw Error("the georeference's CRS must be projected (metres east, north; e.g. a UTM "
                "zone), got '" + crs + "'");
  if (type == PJ_TYPE_PROJECTED_CRS) {
    Pj cs(proj_crs_get_coordinate_system(ctx, pj.get()));
    if (cs && proj_cs_get_axis_count(ctx, cs.get()) == 2) {
      Pj promoted(proj_crs_promote_to_3D(ctx, nullptr, pj.get()));
      if (!promoted) throw Error("cannot give CRS '" + crs + "' a height axis: " + proj_error(ctx));
      return promoted;
    }
  }
  return pj;
}

// Checks that `m` is a similarity: last row (0 0 0 1), linear part a
// positive scale times a rotation. Returns the scale.
double similarity_scale(const Mat4& m, const std::string& name) {
  if (!m.allFinite()) throw Error("the transform has non-finite numbers", name);
  if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 2) != 0 || m(3, 3) != 1)
    throw Error("the transform's last row must be 0 0 0 1", name);
  const Mat3 a = m.topLeftCorner<3, 3>();
  const double det = a.determinant();
  if (!(det > 0)) throw Error("the transform must keep orientation (positive determinant)", name);
  const double s = std::cbrt(det);
  const Mat3 r = a / s;
  if ((r.transpose() * r - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-6)
    throw Error("the transform must be a similarity (rotation, uniform scale, translation)", name);
  return s;
}

void check_origin(const Geodetic& o, const std::string& name) {
  if (!(std::abs(o.latitude) <= 90) || !(std::abs(o.longitude) <= 180) || !std::isfinite(o.height) ||
      std::abs(o.height) > 1e5)
    throw Error("the ENU origin must be latitude in [-90, 90], longitude in [-180, 180] and a "
                "height within 100 km of the ellipsoid", name);
}

bool is_geocentric(PJ_CONTEXT* ctx, const std::string& crs) {
  Pj pj(proj_create(ctx, crs.c_str()));
  return pj && proj_get_type(pj.get()) == PJ_TYPE_GEOCENTRIC_CRS;
}

// The exact conversion of a geocentric or ENU frame (after the scene's
// similarity) to WGS84 longitude, latitude, ellipsoidal height.
class CurvedFrame {
 public:
  explicit CurvedFrame(const Georeference& g) : g_(g) {
    similarity_scale(g.scene_to_crs, "georeference");
    PJ_CONTEXT* ctx = ctx_.get();
    proj_log_level(ctx, PJ_LOG_NONE);
    if (g.crs == "ENU") {
      if (!g.enu_origin) throw Error("an ENU georeference needs its origin");
      std::ostringstream p;
      p.precision(17);
      p << "+proj=pipeline +step +inv +proj=topocentric +ellps=WGS84 +lat_0=" << g.enu_origin->latitude
        << " +lon_0=" << g.enu_origin->longitude << " +h_0=" << g.enu_origin->height
        << " +step +inv +proj=cart +ellps=WGS84 +step +proj=unitconvert +xy_in=rad +xy_out=deg";
      op_.reset(proj_create(ctx, p.str().c_str()));
      if (!op_) throw Error("PROJ cannot build the ENU conversion: " + proj_error(ctx));
    } else {
      Pj crs(proj_create(ctx, g.crs.c_str()));
      if (!crs) throw Error("unknown CRS '" + g.crs + "': " + proj_error(ctx));
      if (proj_get_type(crs.get()) != PJ_TYPE_GEOCENTRIC_CRS)
        throw Error("not a geocentric CRS: '" + g.crs + "'");
      Pj wgs84(proj_create(ctx, "EPSG:4979"));
      if (!wgs84) throw Error("PROJ's database lacks WGS84: " + proj_error(ctx));
      op_ = transformation(ctx, crs.get(), wgs84.get(), "from the geocentric CRS to WGS84");
    }
  }
  Geodetic to_wgs84(const Vec3& scene) const {
    const Vec3 c = (g_.scene_to_crs * scene.homogeneous()).head<3>();
    const Vec3 w = run(op_.get(), PJ_FWD, c, "geocentric or ENU to WGS84");
    return {w.y(), w.x(), w.z()};
  }

 private:
  Georeference g_;
  Context ctx_{proj_context_create()};
  Pj op_;
};

std::string utm_zone_crs(const Geodetic& g);

}  // namespace

bool is_curved_frame(const Georeference& g) {
  if (g.crs == "ENU") return true;
  Context ctx(proj_context_create());
  proj_log_level(ctx.get(), PJ_LOG_NONE);
  return is_geocentric(ctx.get(), g.crs);
}

Georeference localize_georef(const Georeference& g, const std::vector<Vec3>& points) {
  if (!is_curved_frame(g)) return g;
  if (points.size() < 3) throw Error("georeferencing needs the scene's points (at least 3)");
  const CurvedFrame exact(g);
  std::vector<Geodetic> geo;
  geo.reserve(points.size());
  Geodetic mean;
  for (const Vec3& p : points) {
    geo.push_back(exact.to_wgs84(p));
    mean.latitude += geo.back().latitude / double(points.size());
    mean.longitude += geo.back().longitude / double(points.size());
  }
  Georeference out;
  out.crs = utm_zone_crs(mean);
  const GeoFrame utm(out);  // identity: for the conversions only
  const auto n = Eigen::Index(points.size());
  Eigen::Matrix3Xd src(3, n), dst(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    src.col(i) = points[std::size_t(i)];
    dst.col(i) = utm.crs_from_wgs84(geo[std::size_t(i)]);
  }
  const Vec3 so = src.rowwise().mean(), offset = dst.rowwise().mean();
  Mat4 t = Eigen::umeyama(src.colwise() - so, dst.colwise() - offset, true);
  // Back to uncentred scene coordinates: x -> T (x - so) + offset.
  t.topRightCorner<3, 1>() += offset - t.topLeftCorner<3, 3>() * so;
  out.scene_to_crs = t;
  double worst = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    worst = std::max(worst, ((t * src.col(i).homogeneous()).head<3>() - dst.col(i)).norm());
  out.deviation_m = worst;
  std::ostringstream why;
  why.precision(3);
  why << g.source << ", expressed in " << out.crs << " (largest deviation " << worst << " m over "
      << points.size() << " scene points)";
  out.source = why.str();
  if (!(worst <= kMaxDeviation))
    throw Error(why.str() + ": the scene spans too much of the Earth's curvature for one similarity "
                "(more than " + std::to_string(int(kMaxDeviation)) + " m); give --georef in a projected CRS");
  return out;
}

std::optional<Georeference> scene_crs_georef(const Scene& scene) {
  if (scene.crs.empty()) return std::nullopt;
  Context ctx(proj_context_create());
  PJ_CONTEXT* c = ctx.get();
  proj_log_level(c, PJ_LOG_NONE);
  Pj crs(proj_create(c, scene.crs.c_str()));
  if (!crs) throw Error("the scene's CRS is not one PROJ reads: " + proj_error(c), scene.source);
  Georeference g;
  g.source = "the scene's own CRS (" + std::string(proj_get_name(crs.get()) ? proj_get_name(crs.get()) : "?") + ")";
  if (!scene.crs_geocentric) {
    g.crs = scene.crs;
    return g;
  }
  // The geocentric CRS of the CRS's datum (or datum ensemble).
  Pj geodetic(proj_crs_get_geodetic_crs(c, crs.get()));
  if (!geodetic) throw Error("the scene's CRS has no geodetic datum: " + proj_error(c), scene.source);
  Pj datum(proj_crs_get_datum_forced(c, geodetic.get()));
  if (!datum) throw Error("the scene's CRS has no geodetic datum: " + proj_error(c), scene.source);
  Pj geocentric(proj_create_geocentric_crs_from_datum(c, "geocentric", datum.get(), "metre", 1.0));
  if (!geocentric) throw Error("no geocentric CRS for the scene's datum: " + proj_error(c), scene.source);
  const char* wkt = proj_as_wkt(c, geocentric.get(), PJ_WKT2_2019, nullptr);
  if (!wkt) throw Error("no geocentric CRS for the scene's datum: " + proj_error(c), scene.source);
  g.crs = wkt;
  g.source += ", geocentric";
  return g;
}

double Georeference::rms_residual() const {
  double s = 0;
  for (double r : residuals) s += r * r;
  return residuals.empty() ? 0.0 : std::sqrt(s / double(residuals.size()));
}

Georeference parse_georef_json(const std::string& text, const std::string& name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    throw Error("not valid JSON", name);
  }
  if (!j.is_object() || !j.contains("crs") || !j["crs"].is_string())
    throw Error("a georeference needs \"crs\" (a string, e.g. \"EPSG:32632\")", name);
  if (!j.contains("transform") || !j["transform"].is_array() || j["transform"].size() != 16)
    throw Error("a georeference needs \"transform\": 16 numbers (row-major 4x4, scene -> CRS)", name);
  Georeference g;
  g.crs = j["crs"].get<std::string>();
  for (int i = 0; i < 16; ++i) {
    const auto& v = j["transform"][std::size_t(i)];
    if (!v.is_number()) throw Error("\"transform\" must hold 16 numbers", name);
    g.scene_to_crs(i / 4, i % 4) = v.get<double>();
  }
  similarity_scale(g.scene_to_crs, name);
  g.source = "georeference file " + name;
  if (g.crs == "ENU") {
    const auto& o = j.contains("origin") ? j["origin"] : nlohmann::json();
    if (!o.is_array() || o.size() != 3 || !o[0].is_number() || !o[1].is_number() || !o[2].is_number())
      throw Error("an \"ENU\" georeference needs \"origin\": [latitude, longitude, ellipsoidal height]", name);
    g.enu_origin = Geodetic{o[0].get<double>(), o[1].get<double>(), o[2].get<double>()};
    check_origin(*g.enu_origin, name);
  }
  try {
    if (is_curved_frame(g))
      CurvedFrame check(g);
    else
      GeoFrame check(g);  // a CRS PROJ does not know fails here, naming it
  } catch (const Error& e) {
    throw Error(e.what(), name);
  }
  return g;
}

Georeference parse_georef_argument(const std::string& a) {
  if (a == "ecef") {
    Georeference g;
    g.crs = "EPSG:4978";
    g.source = "--georef ecef (scene coordinates WGS84 geocentric, EPSG:4978)";
    return g;
  }
  if (a.rfind("enu:", 0) == 0) {
    const std::vector<double> v = comma_numbers(a.substr(4), "--georef");
    if (v.size() != 3)
      throw Error("--georef enu: takes LAT,LON,H (the tangent frame's origin, WGS84 degrees and "
                  "ellipsoidal metres), got '" + a + "'");
    Georeference g;
    g.crs = "ENU";
    g.enu_origin = Geodetic{v[0], v[1], v[2]};
    check_origin(*g.enu_origin, "--georef");
    g.source = "--georef " + a + " (scene coordinates east, north, up from that origin)";
    return g;
  }
  return read_georef_file(a);
}

Georeference read_georef_file(const std::string& path) {
  return parse_georef_json(io::read_file(path), path);
}

std::string georef_json(const Georeference& g) {
  nlohmann::json j;
  j["crs"] = g.crs;
  nlohmann::json t = nlohmann::json::array();
  for (int i = 0; i < 16; ++i) t.push_back(g.scene_to_crs(i / 4, i % 4));
  j["transform"] = t;
  j["source"] = g.source;
  if (!g.residuals.empty()) {
    nlohmann::json r = nlohmann::json::array();
    for (std::size_t i = 0; i < g.residuals.size(); ++i)
      r.push_back({{"view", g.fit_labels[i]}, {"residual_m", g.residuals[i]}});
    j["fit"] = {{"photos", r}, {"rms_residual_m", g.rms_residual()}};
  }
  return j.dump(2) + "\n";
}

std::vector<GpsFix> gps_fixes(const Scene& scene) {
  std::vector<GpsFix> fixes;
  for (const View& v : scene.views) {
    if (v.image_path.empty()) continue;
    const std::optional<io::ExifInfo> e = io::read_exif_if_known_type(v.image_path);
    if (!e || !e->has_gps()) continue;
    fixes.push_back({v.label, v.camera.center(), {*e->latitude, *e->longitude, e->altitude.value_or(0.0)}});
  }
  return fixes;
}

namespace {

// Second singular value over the first of the centred points: 0 when
// collinear or coincident.
double planarity(const Eigen::Matrix3Xd& p) {
  const Eigen::Matrix3Xd c = p.colwise() - p.rowwise().mean();
  const Eigen::JacobiSVD<Eigen::Matrix3Xd> svd(c);
  const Vec3 s = svd.singularValues();
  return s(0) > 0 ? s(1) / s(0) : 0.0;
}

std::string utm_zone_crs(const Geodetic& g) {
  const int zone = std::min(60, std::max(1, int(std::floor((g.longitude + 180.0) / 6.0)) + 1));
  return "EPSG:" + std::to_string((g.latitude >= 0 ? 32600 : 32700) + zone);
}

}  // namespace

Georeference fit_georef(const std::vector<GpsFix>& fixes) {
  if (fixes.size() < 3)
    throw Error("georeferencing from EXIF GPS needs at least 3 photos with GPS, found " +
                std::to_string(fixes.size()) + " (or give --georef FILE)");
  Geodetic mean;
  for (const GpsFix& f : fixes) {
    mean.latitude += f.gps.latitude / double(fixes.size());
    mean.longitude += f.gps.longitude / double(fixes.size());
  }
  Georeference g;
  g.crs = utm_zone_crs(mean);
  GeoFrame frame(g);  // identity: CRS = scene, for the conversions only
  const auto n = Eigen::Index(fixes.size());
  Eigen::Matrix3Xd src(3, n), dst(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    src.col(i) = fixes[std::size_t(i)].scene;
    dst.col(i) = frame.crs_from_wgs84(fixes[std::size_t(i)].gps);
  }
  if (planarity(src) < 0.05 || planarity(dst) < 0.05)
    throw Error("the " + std::to_string(fixes.size()) + " photos with GPS are (nearly) in a line: "
                "georeferencing needs at least 3 well-spread photos (or give --georef FILE)");
  // Centred on the GPS mean so that Umeyama works with small numbers.
  const Vec3 offset = dst.rowwise().mean();
  const Eigen::Matrix3Xd dst_c = dst.colwise() - offset;
  Mat4 t = Eigen::umeyama(src, dst_c, true);
  t.topRightCorner<3, 1>() += offset;
  g.scene_to_crs = t;
  g.source = "EXIF GPS of " + std::to_string(fixes.size()) + " photos (" + g.crs + ")";
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 fitted = (t * src.col(i).homogeneous()).head<3>();
    g.fit_labels.push_back(fixes[std::size_t(i)].label);
    g.residuals.push_back((fitted - dst.col(i)).norm());
  }
  return g;
}

struct GeoFrame::Impl {
  Georeference georef;
  Context ctx{proj_context_create()};
  Pj to_wgs84, to_egm96;
  Mat4 inverse;
  Vec3 up;
  double scale = 1;
  geod_geodesic geod{};
};

GeoFrame::GeoFrame(const Georeference& georef) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.georef = georef;
  m.scale = similarity_scale(georef.scene_to_crs, "georeference");
  m.inverse = georef.scene_to_crs.inverse();
  m.up = georef.scene_to_crs.block<1, 3>(2, 0).transpose().normalized();
  PJ_CONTEXT* ctx = m.ctx.get();
  proj_log_level(ctx, PJ_LOG_NONE);
  Pj crs = crs_3d(ctx, georef.crs);
  Pj wgs84(proj_create(ctx, "EPSG:4979"));
  Pj egm96(proj_create(ctx, "EPSG:4326+5773"));
  if (!wgs84 || !egm96) throw Error("PROJ's database lacks WGS84 or EGM96: " + proj_error(ctx));
  m.to_wgs84 = transformation(ctx, crs.get(), wgs84.get(), "from " + georef.crs + " to WGS84");
  m.to_egm96 = transformation(ctx, wgs84.get(), egm96.get(), "from WGS84 to EGM96 heights");
  geod_init(&m.geod, 6378137.0, 1 / 298.257223563);
}

GeoFrame::~GeoFrame() = default;

const Georeference& GeoFrame::georef() const { return impl_->georef; }
Vec3 GeoFrame::to_crs(const Vec3& p) const {
  return (impl_->georef.scene_to_crs * p.homogeneous()).head<3>();
}
Vec3 GeoFrame::from_crs(const Vec3& p) const { return (impl_->inverse * p.homogeneous()).head<3>(); }

Geodetic GeoFrame::to_wgs84(const Vec3& scene) const {
  const Vec3 g = run(impl_->to_wgs84.get(), PJ_FWD, to_crs(scene), "to WGS84");
  return {g.y(), g.x(), g.z()};
}

Vec3 GeoFrame::crs_from_wgs84(const Geodetic& g) const {
  return run(impl_->to_wgs84.get(), PJ_INV, Vec3(g.longitude, g.latitude, g.height), "from WGS84");
}

Vec3 GeoFrame::from_wgs84(const Geodetic& g) const { return from_crs(crs_from_wgs84(g)); }

double GeoFrame::egm96_height(const Geodetic& g) const {
  return run(impl_->to_egm96.get(), PJ_FWD, Vec3(g.longitude, g.latitude, g.height), "to EGM96").z();
}

double GeoFrame::ellipsoidal_from_egm96(double latitude, double longitude, double egm96) const {
  return run(impl_->to_egm96.get(), PJ_INV, Vec3(longitude, latitude, egm96), "from EGM96").z();
}

const Vec3& GeoFrame::up() const { return impl_->up; }
double GeoFrame::metres_per_unit() const { return impl_->scale; }
double GeoFrame::crs_height(const Vec3& scene) const { return to_crs(scene).z(); }

double GeoFrame::heading(const Vec3& at, const Vec3& dir) const {
  const Vec3 h = dir - dir.dot(up()) * up();
  if (h.norm() < 1e-9 * dir.norm()) return 0.0;
  // A point one metre ahead, both on WGS84: the geodesic azimuth between them.
  const Geodetic a = to_wgs84(at);
  const Geodetic b = to_wgs84(at + h.normalized() / metres_per_unit());
  double s12 = 0, azi1 = 0, azi2 = 0;
  geod_inverse(&impl_->geod, a.latitude, a.longitude, b.latitude, b.longitude, &s12, &azi1, &azi2);
  double deg = std::fmod(azi1 + 360.0, 360.0);
  return deg >= 360.0 ? 0.0 : deg;
}

double GeoFrame::pitch(const Vec3& dir) const {
  const double s = std::max(-1.0, std::min(1.0, dir.normalized().dot(up())));
  return std::asin(s) * 180.0 / kPi;
}

}  // namespace meshnbv::mission
