// Keep-out volumes and the constraint checks of waypoints and legs (airspace.h).
#include "meshnbv/mission/airspace.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "coordinates_text.h"

namespace meshnbv::mission {
namespace {

using nlohmann::json;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

int sign(double x) { return (x > 0) - (x < 0); }

// Closed segments [a, b] and [c, d] share a point.
bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int d1 = sign(cross(c, d, a)), d2 = sign(cross(c, d, b));
  const int d3 = sign(cross(a, b, c)), d4 = sign(cross(a, b, d));
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && on_segment(a, c, d)) || (d2 == 0 && on_segment(b, c, d)) ||
         (d3 == 0 && on_segment(c, a, b)) || (d4 == 0 && on_segment(d, a, b));
}

bool inside_ring(const std::vector<Vec2>& ring, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2& a = ring[i];
    const Vec2& b = ring[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

bool segment_meets_ring(const std::vector<Vec2>& ring, const Vec2& a, const Vec2& b) {
  if (inside_ring(ring, a) || inside_ring(ring, b)) return true;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if (segments_touch(a, b, ring[j], ring[i])) return true;
  return false;
}

// The part [t0, t1] of [0, 1] where lo <= z0 + t (z1 - z0) <= hi; false if none.
bool clip_slab(double z0, double z1, double lo, double hi, double* t0, double* t1) {
  const double dz = z1 - z0;
  if (dz == 0) return z0 >= lo && z0 <= hi;
  double a = (lo - z0) / dz, b = (hi - z0) / dz;
  if (a > b) std::swap(a, b);
  *t0 = std::max(*t0, a);
  *t1 = std::min(*t1, b);
  return *t0 <= *t1;
}

bool segment_meets_box(const Vec3& a, const Vec3& b, const KeepOutBox& box) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k)
    if (!clip_slab(a[k], b[k], box.min[k], box.max[k], &t0, &t1)) return false;
  return true;
}

double number(const json& j, const char* key, double fallback, const std::string& where) {
  if (!j.is_object() || !j.contains(key) || j[key].is_null()) return fallback;
  if (!j[key].is_number()) throw Error(where + ": \"" + key + "\" must be a number");
  return j[key].get<double>();
}

KeepOutPolygon polygon_feature(const json& f, const std::string& where) {
  const json& geom = f.is_object() && f.contains("geometry") ? f["geometry"] : json();
  if (!geom.is_object() || geom.value("type", "") != "Polygon")
    throw Error(where + ": keep-out features must be Polygons");
  const json& rings = geom.contains("coordinates") ? geom["coordinates"] : json();
  if (!rings.is_array() || rings.empty()) throw Error(where + ": a Polygon needs coordinates");
  if (rings.size() > 1) throw Error(where + ": keep-out polygons cannot have holes");
  KeepOutPolygon p;
  const json props = f.contains("properties") && f["properties"].is_object() ? f["properties"] : json::object();
  p.name = props.contains("name") && props["name"].is_string() ? props["name"].get<std::string>() : where;
  p.floor = number(props, "floor", p.floor, where);
  p.ceiling = number(props, "ceiling", p.ceiling, where);
  if (!(p.floor < p.ceiling)) throw Error(where + ": floor must be below ceiling");
  for (const json& c : rings[0]) {
    if (!c.is_array() || c.size() < 2 || !c[0].is_number() || !c[1].is_number())
      throw Error(where + ": a position must be [longitude, latitude]");
    const Vec2 ll(c[0].get<double>(), c[1].get<double>());
    if (!(std::abs(ll.x()) <= 180) || !(std::abs(ll.y()) <= 90))
      throw Error(where + ": position out of range (longitude in [-180, 180], latitude in [-90, 90])");
    if (p.lonlat.empty() || ll != p.lonlat.back()) p.lonlat.push_back(ll);
  }
  if (p.lonlat.size() > 1 && p.lonlat.front() == p.lonlat.back()) p.lonlat.pop_back();
  if (p.lonlat.size() < 3) throw Error(where + ": a keep-out polygon needs at least 3 corners");
  if (ring_self_intersects(p.lonlat)) throw Error(where + ": the keep-out polygon intersects itself");
  return p;
}

}  // namespace

bool ring_self_intersects(const std::vector<Vec2>& r) {
  const std::size_t n = r.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share one corner; they must not fold back onto each other.
        // (i, i+1) meet at r[i+1]; (0, n-1) meet at r[0].
        const bool next = j == i + 1;
        const Vec2& shared = next ? r[j] : r[0];
        const Vec2& p = next ? r[i] : r[1];
        const Vec2& q = next ? r[(j + 1) % n] : r[n - 1];
        if (cross(shared, p, q) == 0 && (p - shared).dot(q - shared) > 0) return true;
        continue;
      }
      if (segments_touch(r[i], r[(i + 1) % n], r[j], r[(j + 1) % n])) return true;
    }
  return false;
}

KeepOuts parse_keep_out_geojson(const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception&) {
    throw Error("not valid JSON", name);
  }
  KeepOuts k;
  try {
    const std::string type = j.is_object() ? j.value("type", "") : "";
    if (type == "Feature") {
      k.polygons.push_back(polygon_feature(j, "feature 0"));
    } else if (type == "FeatureCollection" && j.contains("features") && j["features"].is_array()) {
      for (std::size_t i = 0; i < j["features"].size(); ++i)
        k.polygons.push_back(polygon_feature(j["features"][i], "feature " + std::to_string(i)));
    } else {
      throw Error("keep-out volumes must be a GeoJSON FeatureCollection or Feature");
    }
  } catch (const json::exception& e) {
    throw Error(std::string("malformed GeoJSON: ") + e.what(), name);
  } catch (const Error& e) {
    throw Error(e.reason(), name);
  }
  return k;
}

KeepOuts read_keep_out_geojson(const std::string& path) {
  return parse_keep_out_geojson(io::read_file(path), path);
}

KeepOutBox parse_keep_out_box(const std::string& text) {
  const std::vector<double> v = comma_numbers(text, "--keep-out-box");
  if (v.size() != 6)
    throw Error("--keep-out-box takes xmin,ymin,zmin,xmax,ymax,zmax (scene coordinates), got '" + text + "'");
  KeepOutBox b;
  b.name = "box " + text;
  b.min = Vec3(v[0], v[1], v[2]);
  b.max = Vec3(v[3], v[4], v[5]);
  if (!(b.min.array() < b.max.array()).all())
    throw Error("--keep-out-box: each min must be below its max, got '" + text + "'");
  return b;
}

Airspace::Airspace(const RayCaster& caster, const GeoFrame& frame, const Vec3& takeoff,
                   const MissionOptions& options, const KeepOuts& keep_outs)
    : caster_(caster),
      frame_(frame),
      takeoff_(takeoff),
      takeoff_height_(frame.crs_height(takeoff)),
      options_(options),
      keep_outs_(keep_outs),
      clearance_(options.min_mesh_distance / frame.metres_per_unit()) {
  options_.check();
  const double h = frame.to_wgs84(takeoff).height;
  for (const KeepOutPolygon& p : keep_outs_.polygons) {
    std::vector<Vec2> ring;
    for (const Vec2& ll : p.lonlat) ring.push_back(frame.crs_from_wgs84({ll.y(), ll.x(), h}).head<2>());
    rings_crs_.push_back(std::move(ring));
  }
}

double Airspace::height(const Vec3& p) const { return frame_.crs_height(p) - takeoff_height_; }

std::string Airspace::point_problem(const Vec3& p) const {
  std::ostringstream why;
  const double h = height(p);
  if (h < options_.min_altitude) {
    why << "altitude " << h << " m is below min_altitude " << options_.min_altitude << " m";
    return why.str();
  }
  if (h > options_.max_altitude) {
    why << "altitude " << h << " m is above max_altitude " << options_.max_altitude << " m";
    return why.str();
  }
  const double d = caster_.closest_point(p);
  if (d < clearance_) {
    why << "distance to the mesh " << d * frame_.metres_per_unit() << " m is below min_mesh_distance "
        << options_.min_mesh_distance << " m";
    return why.str();
  }
  return keep_out_problem(p, p);
}

std::string Airspace::keep_out_problem(const Vec3& a, const Vec3& b) const {
  for (const KeepOutBox& box : keep_outs_.boxes)
    if (segment_meets_box(a, b, box)) return "inside keep-out " + box.name;
  const Vec3 ca = frame_.to_crs(a), cb = frame_.to_crs(b);
  for (std::size_t i = 0; i < rings_crs_.size(); ++i) {
    const KeepOutPolygon& p = keep_outs_.polygons[i];
    double t0 = 0, t1 = 1;
    if (!clip_slab(ca.z() - takeoff_height_, cb.z() - takeoff_height_, p.floor, p.ceiling, &t0, &t1))
      continue;
    const Vec3 p0 = ca + t0 * (cb - ca), p1 = ca + t1 * (cb - ca);
    if (segment_meets_ring(rings_crs_[i], p0.head<2>(), p1.head<2>()))
      return "inside keep-out " + p.name;
  }
  return {};
}

// Sphere tracing: the distance to the mesh is 1-Lipschitz, so a point at
// distance r certifies the ball of radius r - clearance around it. A leg
// passes when every step is at least 2% of the clearance.
std::string Airspace::mesh_problem(const Vec3& a, const Vec3& b) const {
  const double length = (b - a).norm();
  const double eps = 0.02 * clearance_;
  double t = 0;
  for (;;) {
    const Vec3 p = length > 0 ? Vec3(a + (b - a) * (t / length)) : a;
    const double r = caster_.closest_point(p);
    if (r - clearance_ < eps) {
      std::ostringstream why;
      why << "passes " << r * frame_.metres_per_unit() << " m from the mesh (min_mesh_distance "
          << options_.min_mesh_distance << " m)";
      return why.str();
    }
    if (t >= length) return {};
    t = std::min(length, t + (r - clearance_));
  }
}

std::string Airspace::leg_problem(const Vec3& a, const Vec3& b, bool takeoff_leg) const {
  for (const Vec3* p : {&a, &b}) {
    const double h = height(*p);
    if ((!takeoff_leg && h < options_.min_altitude - 1e-9) || h > options_.max_altitude + 1e-9) {
      std::ostringstream why;
      why << "leg reaches altitude " << h << " m, outside [" << options_.min_altitude << ", "
          << options_.max_altitude << "] m";
      return why.str();
    }
  }
  std::string why = keep_out_problem(a, b);
  if (!why.empty()) return "leg passes " + why;
  if (takeoff_leg) {
    // From just above the ground: the climb must not pass through the mesh.
    const Vec3 d = b - a;
    const double len = d.norm();
    const double start = std::min(0.5 * len, 0.01 * clearance_);
    if (len > 0 && caster_.occluded(a, d / len, start, len))
      return "the vertical take-off leg passes through the mesh";
    return {};
  }
  why = mesh_problem(a, b);
  return why.empty() ? why : "leg " + why;
}

}  // namespace meshnbv::mission
