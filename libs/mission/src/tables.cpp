// litchi.csv, waypoints.csv, mission.geojson and mission.json (writers.h).
#include <cmath>

#include <nlohmann/json.hpp>

#include "flight_points.h"
#include "meshnbv/mission/writers.h"
#include "meshnbv/options.h"

namespace meshnbv::mission {

const char* const kLitchiHeader =
    "latitude,longitude,altitude(m),heading(deg),curvesize(m),rotationdir,gimbalmode,"
    "gimbalpitchangle,actiontype1,actionparam1,actiontype2,actionparam2,actiontype3,actionparam3,"
    "actiontype4,actionparam4,actiontype5,actionparam5,actiontype6,actionparam6,actiontype7,"
    "actionparam7,actiontype8,actionparam8,actiontype9,actionparam9,actiontype10,actionparam10,"
    "actiontype11,actionparam11,actiontype12,actionparam12,actiontype13,actionparam13,actiontype14,"
    "actionparam14,actiontype15,actionparam15,altitudemode,speed(m/s),poi_latitude,poi_longitude,"
    "poi_altitude(m),poi_altitudemode,photo_timeinterval,photo_distinterval";

std::string litchi_csv(const MissionPlan& plan, std::size_t flight, const GeoFrame& frame,
                       const MissionOptions& o) {
  std::string out = std::string(kLitchiHeader) + "\n";
  for (const OutPoint& p : flight_points(plan, flight, frame)) {
    // Altitude above the take-off point (altitudemode 0); gimbal mode 2 =
    // interpolate to gimbalpitchangle; action 1 = take a photo.
    out += fixed(p.geo.latitude, 10) + "," + fixed(p.geo.longitude, 10) + "," + fixed(p.height, 4) +
           "," + fixed(p.heading, 4) + ",0,0,2," + fixed(p.pitch, 4) + "," +
           (p.waypoint >= 0 ? "1,0" : "-1,0");
    for (int a = 2; a <= 15; ++a) out += ",-1,0";
    out += ",0," + fixed(o.speed, 2) + ",0,0,0,0,-1,-1\n";
  }
  return out;
}

std::string waypoints_csv(const MissionPlan& plan) {
  std::string out =
      "flight,order,label,rank,x,y,z,latitude,longitude,ellipsoidal_height,height_above_takeoff,"
      "heading,gimbal_pitch,moved,moved_by_m,energy\n";
  for (const Waypoint& w : plan.waypoints) {
    out += std::to_string(w.flight + 1) + "," + std::to_string(w.order + 1) + "," + w.label + "," +
           std::to_string(w.rank) + "," + fixed(w.position.x(), 6) + "," + fixed(w.position.y(), 6) +
           "," + fixed(w.position.z(), 6) + "," + fixed(w.geo.latitude, 10) + "," +
           fixed(w.geo.longitude, 10) + "," + fixed(w.geo.height, 4) + "," + fixed(w.height, 4) +
           "," + fixed(w.heading, 4) + "," + fixed(w.pitch, 4) + "," + (w.moved ? "1" : "0") + "," +
           fixed(w.moved_by, 3) + "," + (std::isfinite(w.energy) ? fixed(w.energy, 6) : "") + "\n";
  }
  return out;
}

namespace {
using nlohmann::json;
json position(const Geodetic& g) {
  return json::array({std::stod(fixed(g.longitude, 10)), std::stod(fixed(g.latitude, 10)),
                      std::stod(fixed(g.height, 4))});
}
json feature(json geometry, json properties) {
  return {{"type", "Feature"}, {"geometry", std::move(geometry)}, {"properties", std::move(properties)}};
}
}  // namespace

std::string mission_geojson(const MissionPlan& plan, const GeoFrame& frame, const KeepOuts& keep_outs) {
  json features = json::array();
  features.push_back(feature({{"type", "Point"}, {"coordinates", position(plan.takeoff_geo)}},
                             {{"kind", "takeoff"}}));
  for (std::size_t k = 0; k < plan.flights.size(); ++k) {
    json line = json::array({position(plan.takeoff_geo)});
    for (const OutPoint& p : flight_points(plan, k, frame)) line.push_back(position(p.geo));
    line.push_back(position(plan.takeoff_geo));
    features.push_back(feature({{"type", "LineString"}, {"coordinates", line}},
                               {{"kind", "path"}, {"flight", k + 1},
                                {"minutes", plan.flights[k].minutes},
                                {"length_m", plan.flights[k].length_m}}));
  }
  for (const Waypoint& w : plan.waypoints)
    features.push_back(feature(
        {{"type", "Point"}, {"coordinates", position(w.geo)}},
        {{"kind", "photo"}, {"label", w.label}, {"flight", w.flight + 1}, {"order", w.order + 1},
         {"heading", w.heading}, {"gimbal_pitch", w.pitch}, {"height_above_takeoff", w.height},
         {"scene", {w.position.x(), w.position.y(), w.position.z()}}, {"moved", w.moved}}));
  for (const KeepOutPolygon& p : keep_outs.polygons) {
    json ring = json::array();
    for (const Vec2& ll : p.lonlat) ring.push_back({ll.x(), ll.y()});
    ring.push_back({p.lonlat.front().x(), p.lonlat.front().y()});
    json props = {{"kind", "keep_out"}, {"name", p.name}};
    if (std::isfinite(p.floor)) props["floor"] = p.floor;
    if (std::isfinite(p.ceiling)) props["ceiling"] = p.ceiling;
    features.push_back(feature({{"type", "Polygon"}, {"coordinates", json::array({ring})}}, props));
  }
  return json({{"type", "FeatureCollection"}, {"features", features}}).dump(1) + "\n";
}

std::string mission_summary_json(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& o) {
  json j;
  j["format"] = "meshnbv-mission";
  j["version"] = 1;
  j["georeference"] = json::parse(georef_json(frame.georef()));
  j["takeoff"] = {{"scene", {plan.takeoff.x(), plan.takeoff.y(), plan.takeoff.z()}},
                  {"latitude", plan.takeoff_geo.latitude}, {"longitude", plan.takeoff_geo.longitude},
                  {"ellipsoidal_height", plan.takeoff_geo.height}};
  j["climb_height_m"] = plan.climb_height;
  json flights = json::array();
  for (std::size_t k = 0; k < plan.flights.size(); ++k) {
    json labels = json::array();
    for (int w : plan.flights[k].waypoints) labels.push_back(plan.waypoints[std::size_t(w)].label);
    flights.push_back({{"flight", k + 1}, {"photos", labels}, {"minutes", plan.flights[k].minutes},
                       {"length_m", plan.flights[k].length_m}, {"detours", plan.flights[k].detours}});
  }
  j["flights"] = flights;
  j["total_minutes"] = plan.total_minutes();
  json notes = json::array();
  for (const Note& n : plan.notes)
    notes.push_back({{"label", n.label}, {"action", n.action}, {"reason", n.reason}});
  j["notes"] = notes;
  j["options"] = json::parse(options_json(o, mission_option_table()));
  return j.dump(2) + "\n";
}

std::vector<std::pair<std::string, std::string>> mission_files(const MissionPlan& plan,
                                                               const GeoFrame& frame,
                                                               const MissionOptions& o,
                                                               const KeepOuts& keep_outs,
                                                               const TriangleMesh* mesh) {
  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back("mission.kml", mission_kml(plan, frame));
  files.emplace_back("mission.kmz", mission_kmz(plan, frame, o));
  if (plan.flights.size() == 1) {
    files.emplace_back("litchi.csv", litchi_csv(plan, 0, frame, o));
  } else {
    for (std::size_t k = 0; k < plan.flights.size(); ++k)
      files.emplace_back("litchi_" + std::to_string(k + 1) + ".csv", litchi_csv(plan, k, frame, o));
  }
  files.emplace_back("mission.geojson", mission_geojson(plan, frame, keep_outs));
  files.emplace_back("waypoints.csv", waypoints_csv(plan));
  files.emplace_back("mission.json", mission_summary_json(plan, frame, o));
  if (mesh) files.emplace_back("mission.svg", mission_svg(plan, frame, *mesh, keep_outs));
  return files;
}

}  // namespace meshnbv::mission
