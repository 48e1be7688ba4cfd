// mission.kml and the DJI WPML archive (writers.h).
#include <ctime>
#include <sstream>

#include <pugixml.hpp>
#include <zip.h>

#include "flight_points.h"
#include "meshnbv/error.h"
#include "meshnbv/mission/writers.h"

namespace meshnbv::mission {

std::vector<OutPoint> flight_points(const MissionPlan& plan, std::size_t flight, const GeoFrame& frame) {
  const Flight& f = plan.flights.at(flight);
  std::vector<OutPoint> out;
  for (const PathPoint& p : f.points) {
    OutPoint o;
    o.geo = frame.to_wgs84(p.position);
    o.height = o.geo.height - plan.takeoff_geo.height;
    o.waypoint = p.waypoint;
    out.push_back(o);
  }
  // Path points face like the next photo (the last ones like the last photo).
  int next = f.waypoints.empty() ? -1 : f.waypoints.back();
  for (std::size_t i = out.size(); i-- > 0;) {
    if (out[i].waypoint >= 0) next = out[i].waypoint;
    if (next >= 0) {
      out[i].heading = plan.waypoints[std::size_t(next)].heading;
      out[i].pitch = plan.waypoints[std::size_t(next)].pitch;
    }
  }
  return out;
}

namespace {

using pugi::xml_node;

xml_node text(xml_node parent, const char* name, const std::string& value) {
  xml_node n = parent.append_child(name);
  n.text().set(value.c_str());
  return n;
}

std::string to_string(const pugi::xml_document& doc) {
  std::ostringstream out;
  doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  return out.str();
}

xml_node kml_document(pugi::xml_document* doc, bool wpml) {
  xml_node decl = doc->prepend_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  xml_node kml = doc->append_child("kml");
  kml.append_attribute("xmlns") = "http://www.opengis.net/kml/2.2";
  if (wpml) kml.append_attribute("xmlns:wpml") = "http://www.dji.com/wpmz/1.0.2";
  return kml.append_child("Document");
}

std::string lon_lat(const Geodetic& g) { return fixed(g.longitude, 10) + "," + fixed(g.latitude, 10); }

}  // namespace

std::string mission_kml(const MissionPlan& plan, const GeoFrame& frame) {
  pugi::xml_document doc;
  xml_node d = kml_document(&doc, false);
  text(d, "name", "MeshNBV mission");
  text(d, "description", "Suggested views of MeshNBV. Altitudes are absolute: EGM96 heights "
                         "(above mean sea level), as KML defines them.");
  auto egm = [&](const Geodetic& g) { return fixed(frame.egm96_height(g), 4); };
  xml_node t = d.append_child("Placemark");
  text(t, "name", "take-off");
  xml_node tp = t.append_child("Point");
  text(tp, "altitudeMode", "absolute");
  text(tp, "coordinates", lon_lat(plan.takeoff_geo) + "," + egm(plan.takeoff_geo));
  for (std::size_t k = 0; k < plan.flights.size(); ++k) {
    const std::vector<OutPoint> pts = flight_points(plan, k, frame);
    xml_node folder = d.append_child("Folder");
    text(folder, "name", "flight " + std::to_string(k + 1) + " (" + fixed(plan.flights[k].minutes, 1) + " min)");
    xml_node path = folder.append_child("Placemark");
    text(path, "name", "path " + std::to_string(k + 1));
    xml_node line = path.append_child("LineString");
    text(line, "altitudeMode", "absolute");
    std::string coords = lon_lat(plan.takeoff_geo) + "," + egm(plan.takeoff_geo);
    for (const OutPoint& p : pts) coords += " " + lon_lat(p.geo) + "," + egm(p.geo);
    coords += " " + lon_lat(plan.takeoff_geo) + "," + egm(plan.takeoff_geo);
    text(line, "coordinates", coords);
    for (const OutPoint& p : pts) {
      if (p.waypoint < 0) continue;
      const Waypoint& w = plan.waypoints[std::size_t(p.waypoint)];
      xml_node pm = folder.append_child("Placemark");
      text(pm, "name", w.label);
      xml_node cam = pm.append_child("Camera");
      text(cam, "longitude", fixed(p.geo.longitude, 10));
      text(cam, "latitude", fixed(p.geo.latitude, 10));
      text(cam, "altitude", egm(p.geo));
      text(cam, "heading", fixed(p.heading, 4));
      text(cam, "tilt", fixed(90.0 + p.pitch, 4));  // KML: 0 = straight down, 90 = horizon
      text(cam, "roll", "0");
      text(cam, "altitudeMode", "absolute");
      xml_node pt = pm.append_child("Point");
      text(pt, "altitudeMode", "absolute");
      text(pt, "coordinates", lon_lat(p.geo) + "," + egm(p.geo));
    }
  }
  return to_string(doc);
}

namespace {

void mission_config(xml_node d, const MissionPlan& plan, const MissionOptions& o, bool tmpl) {
  xml_node mc = d.append_child("wpml:missionConfig");
  text(mc, "wpml:flyToWaylineMode", "safely");
  text(mc, "wpml:finishAction", "goHome");
  text(mc, "wpml:exitOnRCLost", "executeLostAction");
  text(mc, "wpml:executeRCLostAction", "goBack");
  text(mc, "wpml:takeOffSecurityHeight", fixed(std::max(1.5, plan.climb_height), 2));
  if (tmpl)
    text(mc, "wpml:takeOffRefPoint", fixed(plan.takeoff_geo.latitude, 10) + "," +
                                         fixed(plan.takeoff_geo.longitude, 10) + "," +
                                         fixed(plan.takeoff_geo.height, 4));
  text(mc, "wpml:globalTransitionalSpeed", fixed(o.speed, 2));
  // Mavic 3 Enterprise (drone 77/0, payload 66): DJI's enumeration values.
  xml_node di = mc.append_child("wpml:droneInfo");
  text(di, "wpml:droneEnumValue", "77");
  text(di, "wpml:droneSubEnumValue", "0");
  xml_node pi = mc.append_child("wpml:payloadInfo");
  text(pi, "wpml:payloadEnumValue", "66");
  text(pi, "wpml:payloadSubEnumValue", "0");
  text(pi, "wpml:payloadPositionIndex", "0");
}

void heading_param(xml_node pm, double heading) {
  xml_node h = pm.append_child("wpml:waypointHeadingParam");
  text(h, "wpml:waypointHeadingMode", "smoothTransition");
  text(h, "wpml:waypointHeadingAngle", fixed(heading > 180 ? heading - 360 : heading, 4));
  text(h, "wpml:waypointPoiPoint", "0.000000,0.000000,0.000000");
  text(h, "wpml:waypointHeadingAngleEnable", "1");
  text(h, "wpml:waypointHeadingPathMode", "followBadArc");
  xml_node t = pm.append_child("wpml:waypointTurnParam");
  text(t, "wpml:waypointTurnMode", "toPointAndStopWithDiscontinuityCurvature");
  text(t, "wpml:waypointTurnDampingDist", "0");
  text(pm, "wpml:useStraightLine", "1");
}

// Gimbal to the photo's pitch, then a photo, on reaching waypoint `index`.
void photo_actions(xml_node pm, int index, int group, double pitch) {
  xml_node g = pm.append_child("wpml:actionGroup");
  text(g, "wpml:actionGroupId", std::to_string(group));
  text(g, "wpml:actionGroupStartIndex", std::to_string(index));
  text(g, "wpml:actionGroupEndIndex", std::to_string(index));
  text(g, "wpml:actionGroupMode", "sequence");
  text(g.append_child("wpml:actionTrigger"), "wpml:actionTriggerType", "reachPoint");
  xml_node a = g.append_child("wpml:action");
  text(a, "wpml:actionId", "0");
  text(a, "wpml:actionActuatorFunc", "gimbalRotate");
  xml_node ap = a.append_child("wpml:actionActuatorFuncParam");
  text(ap, "wpml:gimbalRotateMode", "absoluteAngle");
  text(ap, "wpml:gimbalPitchRotateEnable", "1");
  text(ap, "wpml:gimbalPitchRotateAngle", fixed(pitch, 4));
  text(ap, "wpml:gimbalRollRotateEnable", "0");
  text(ap, "wpml:gimbalRollRotateAngle", "0");
  text(ap, "wpml:gimbalYawRotateEnable", "0");
  text(ap, "wpml:gimbalYawRotateAngle", "0");
  text(ap, "wpml:gimbalRotateTimeEnable", "0");
  text(ap, "wpml:gimbalRotateTime", "0");
  text(ap, "wpml:payloadPositionIndex", "0");
  xml_node b = g.append_child("wpml:action");
  text(b, "wpml:actionId", "1");
  text(b, "wpml:actionActuatorFunc", "takePhoto");
  xml_node bp = b.append_child("wpml:actionActuatorFuncParam");
  text(bp, "wpml:fileSuffix", "");
  text(bp, "wpml:payloadPositionIndex", "0");
}

}  // namespace

std::string wpml_template_kml(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& o) {
  pugi::xml_document doc;
  xml_node d = kml_document(&doc, true);
  const std::string now = std::to_string(std::time(nullptr) * 1000LL);
  text(d, "wpml:author", "MeshNBV");
  text(d, "wpml:createTime", now);
  text(d, "wpml:updateTime", now);
  mission_config(d, plan, o, true);
  for (std::size_t k = 0; k < plan.flights.size(); ++k) {
    xml_node f = d.append_child("Folder");
    text(f, "wpml:templateType", "waypoint");
    text(f, "wpml:templateId", std::to_string(k));
    xml_node cs = f.append_child("wpml:waylineCoordinateSysParam");
    text(cs, "wpml:coordinateMode", "WGS84");
    text(cs, "wpml:heightMode", "relativeToStartPoint");
    text(f, "wpml:autoFlightSpeed", fixed(o.speed, 2));
    text(f, "wpml:globalHeight", fixed(plan.climb_height, 4));
    text(f, "wpml:caliFlightEnable", "0");
    text(f, "wpml:gimbalPitchMode", "usePointSetting");
    text(f.append_child("wpml:globalWaypointHeadingParam"), "wpml:waypointHeadingMode", "smoothTransition");
    text(f, "wpml:globalWaypointTurnMode", "toPointAndStopWithDiscontinuityCurvature");
    text(f, "wpml:globalUseStraightLine", "1");
    const std::vector<OutPoint> pts = flight_points(plan, k, frame);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const OutPoint& p = pts[i];
      xml_node pm = f.append_child("Placemark");
      text(pm.append_child("Point"), "coordinates", lon_lat(p.geo));
      text(pm, "wpml:index", std::to_string(i));
      text(pm, "wpml:ellipsoidHeight", fixed(p.geo.height, 4));
      text(pm, "wpml:height", fixed(p.height, 4));
      text(pm, "wpml:useGlobalHeight", "0");
      text(pm, "wpml:useGlobalSpeed", "1");
      text(pm, "wpml:useGlobalHeadingParam", "0");
      text(pm, "wpml:useGlobalTurnParam", "0");
      text(pm, "wpml:gimbalPitchAngle", fixed(p.pitch, 4));
      heading_param(pm, p.heading);
      if (p.waypoint >= 0) photo_actions(pm, int(i), int(i), p.pitch);
    }
  }
  return to_string(doc);
}

std::string wpml_waylines(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& o) {
  pugi::xml_document doc;
  xml_node d = kml_document(&doc, true);
  mission_config(d, plan, o, false);
  for (std::size_t k = 0; k < plan.flights.size(); ++k) {
    xml_node f = d.append_child("Folder");
    text(f, "wpml:templateId", std::to_string(k));
    text(f, "wpml:executeHeightMode", "WGS84");  // ellipsoidal heights
    text(f, "wpml:waylineId", std::to_string(k));
    text(f, "wpml:distance", fixed(plan.flights[k].length_m, 2));
    text(f, "wpml:duration", fixed(plan.flights[k].minutes * 60.0, 1));
    text(f, "wpml:autoFlightSpeed", fixed(o.speed, 2));
    const std::vector<OutPoint> pts = flight_points(plan, k, frame);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const OutPoint& p = pts[i];
      xml_node pm = f.append_child("Placemark");
      text(pm.append_child("Point"), "coordinates", lon_lat(p.geo));
      text(pm, "wpml:index", std::to_string(i));
      text(pm, "wpml:executeHeight", fixed(p.geo.height, 4));
      text(pm, "wpml:waypointSpeed", fixed(o.speed, 2));
      heading_param(pm, p.heading);
      if (p.waypoint >= 0) photo_actions(pm, int(i), int(i), p.pitch);
    }
  }
  return to_string(doc);
}

namespace {

struct ZipDeleter {
  void operator()(zip_t* z) const { zip_discard(z); }
};

void add_entry(zip_t* z, const std::string& name, const std::string& content) {
  zip_source_t* src = zip_source_buffer(z, content.data(), content.size(), 0);
  if (!src || zip_file_add(z, name.c_str(), src, ZIP_FL_ENC_UTF_8) < 0) {
    if (src) zip_source_free(src);
    throw Error("cannot add " + name + " to the KMZ: " + zip_strerror(z));
  }
}

}  // namespace

std::string mission_kmz(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& o) {
  const std::string tmpl = wpml_template_kml(plan, frame, o);
  const std::string lines = wpml_waylines(plan, frame, o);
  zip_error_t err;
  zip_error_init(&err);
  zip_source_t* buffer = zip_source_buffer_create(nullptr, 0, 0, &err);
  if (!buffer) throw Error("cannot create the KMZ archive in memory");
  zip_source_keep(buffer);
  zip_t* z = zip_open_from_source(buffer, ZIP_TRUNCATE, &err);
  if (!z) {
    zip_source_free(buffer);
    throw Error("cannot create the KMZ archive in memory");
  }
  try {
    add_entry(z, "wpmz/template.kml", tmpl);
    add_entry(z, "wpmz/waylines.wpml", lines);
  } catch (...) {
    zip_discard(z);
    zip_source_free(buffer);
    throw;
  }
  if (zip_close(z) < 0) {
    zip_discard(z);
    zip_source_free(buffer);
    throw Error("cannot write the KMZ archive");
  }
  std::string bytes;
  zip_stat_t st;
  if (zip_source_stat(buffer, &st) == 0 && zip_source_open(buffer) == 0) {
    bytes.resize(std::size_t(st.size));
    const zip_int64_t n = zip_source_read(buffer, bytes.data(), st.size);
    zip_source_close(buffer);
    if (n != zip_int64_t(st.size)) bytes.clear();
  }
  zip_source_free(buffer);
  if (bytes.empty()) throw Error("cannot read back the KMZ archive");
  return bytes;
}

}  // namespace meshnbv::mission
