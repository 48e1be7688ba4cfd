// The mission files (meshnbv::mission, writers.h), parsed back: every format
// gives back the scene positions of its points within 1 cm (scene -> WGS84
// -> file -> WGS84 -> scene); the KMZ holds DJI WPML's documented files,
// element names and required fields; the Litchi CSV has Litchi's exact header.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <zip.h>

#include "meshnbv/mission/writers.h"
#include "meshnbv/raycaster.h"
#include "test_util.h"

namespace meshnbv::test {
namespace {

using namespace meshnbv::mission;

struct Fixture {
  TriangleMesh mesh;
  Georeference georef;
  MissionOptions options;
  std::unique_ptr<GeoFrame> frame;
  std::unique_ptr<RayCaster> caster;
  std::unique_ptr<Airspace> air;
  MissionPlan plan;
  KeepOuts keep_outs;

  explicit Fixture(double battery_minutes) {
    // A 10 x 10 x 10 m cube on the ground; scene units of 0.5 m, rotated 30 degrees about z.
    const double s = 0.5, a = M_PI / 6;
    for (int i = 0; i < 8; ++i)
      mesh.vertices.emplace_back(i & 1 ? 10 : -10, i & 2 ? 10 : -10, i & 4 ? 20 : 0);
    const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& t : f) mesh.faces.push_back({t[0], t[1], t[2]});
    georef.crs = "EPSG:32633";
    georef.scene_to_crs.topLeftCorner<3, 3>() = s * Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
    georef.scene_to_crs.topRightCorner<3, 1>() = Vec3(412345.678, 5650000.123, 87.5);
    frame = std::make_unique<GeoFrame>(georef);
    caster = std::make_unique<RayCaster>(mesh);
    options.battery_minutes = battery_minutes;
    options.max_waypoints = 5;
    KeepOutBox box{"box", Vec3(-14, -40, 0), Vec3(14, -30, 60)};
    keep_outs.boxes.push_back(box);
    air = std::make_unique<Airspace>(*caster, *frame, Vec3(60, 0, 0), options, keep_outs);
    std::vector<MissionInput> in;
    for (int i = 0; i < 9; ++i) {
      const double b = 2 * M_PI * i / 9;
      MissionInput m;
      m.label = "nbv_" + std::to_string(i + 1);
      m.rank = i + 1;
      m.look_at = Vec3(10 * std::cos(b), 10 * std::sin(b), 10).cwiseMax(Vec3(-10, -10, 0)).cwiseMin(Vec3(10, 10, 20));
      const Vec3 eye(40 * std::cos(b), 40 * std::sin(b), 30 + i);
      m.camera = PinholeCamera::look_at(eye, m.look_at, Vec3::UnitZ(), 3000, 3000, 2000, 1500, 4000, 3000);
      in.push_back(m);
    }
    plan = plan_mission(in, *air);
  }

  double error_m(const Geodetic& g, const Vec3& scene) const {
    return (frame->from_wgs84(g) - scene).norm() * frame->metres_per_unit();
  }
  // The scene positions every format lists for flight k, in order.
  std::vector<Vec3> flight_positions(std::size_t k) const {
    std::vector<Vec3> out;
    for (const PathPoint& p : plan.flights[k].points) out.push_back(p.position);
    return out;
  }
};

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, sep)) out.push_back(item);
  return out;
}

TEST(MissionFormats, KmlRoundTripWithinOneCentimetre) {
  const Fixture fx(60);
  ASSERT_EQ(fx.plan.flights.size(), 2u);  // 9 photos, at most 5 per flight
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(mission_kml(fx.plan, *fx.frame).c_str()));
  std::size_t photo = 0;
  for (const pugi::xpath_node& n : doc.select_nodes("/kml/Document/Folder/Placemark[Camera]")) {
    const pugi::xml_node cam = n.node().child("Camera");
    ASSERT_LT(photo, fx.plan.waypoints.size());
    const Waypoint& w = fx.plan.waypoints[photo++];
    EXPECT_EQ(std::string(n.node().child_value("name")), w.label);
    const double lat = cam.child("latitude").text().as_double(), lon = cam.child("longitude").text().as_double();
    const double h = fx.frame->ellipsoidal_from_egm96(lat, lon, cam.child("altitude").text().as_double());
    EXPECT_LT(fx.error_m({lat, lon, h}, w.position), 0.01);
    EXPECT_NEAR(cam.child("heading").text().as_double(), w.heading, 1e-3);
    EXPECT_NEAR(cam.child("tilt").text().as_double(), 90 + w.pitch, 1e-3);
    EXPECT_STREQ(cam.child_value("altitudeMode"), "absolute");
  }
  EXPECT_EQ(photo, fx.plan.waypoints.size());
  // Paths: take-off, the flight's points, take-off.
  std::size_t k = 0;
  for (const pugi::xpath_node& n : doc.select_nodes("/kml/Document/Folder/Placemark/LineString")) {
    const std::vector<std::string> coords = split(n.node().child_value("coordinates"), ' ');
    std::vector<Vec3> want = fx.flight_positions(k++);
    want.insert(want.begin(), fx.plan.takeoff);
    want.push_back(fx.plan.takeoff);
    ASSERT_EQ(coords.size(), want.size());
    for (std::size_t i = 0; i < coords.size(); ++i) {
      const std::vector<std::string> c = split(coords[i], ',');
      const double lat = std::stod(c[1]), lon = std::stod(c[0]);
      EXPECT_LT(fx.error_m({lat, lon, fx.frame->ellipsoidal_from_egm96(lat, lon, std::stod(c[2]))}, want[i]), 0.01);
    }
  }
  EXPECT_EQ(k, fx.plan.flights.size());
}

std::string zip_entry(zip_t* z, const char* name) {
  zip_stat_t st;
  if (zip_stat(z, name, 0, &st) != 0) return {};
  zip_file_t* f = zip_fopen(z, name, 0);
  std::string out(std::size_t(st.size), '\0');
  EXPECT_EQ(zip_fread(f, out.data(), st.size), zip_int64_t(st.size));
  zip_fclose(f);
  return out;
}

// Every listed child exists (DJI WPML's required fields).
void expect_children(const pugi::xml_node& n, std::initializer_list<const char*> names) {
  for (const char* c : names) EXPECT_TRUE(n.child(c)) << n.name() << " lacks " << c;
}

void check_wpml_placemark(const pugi::xml_node& pm, bool tmpl) {
  expect_children(pm, {"Point", "wpml:index", "wpml:waypointHeadingParam", "wpml:waypointTurnParam"});
  if (tmpl) expect_children(pm, {"wpml:ellipsoidHeight", "wpml:height", "wpml:useGlobalHeight",
                                 "wpml:useGlobalSpeed", "wpml:useGlobalHeadingParam", "wpml:useGlobalTurnParam"});
  else expect_children(pm, {"wpml:executeHeight", "wpml:waypointSpeed"});
  expect_children(pm.child("wpml:waypointHeadingParam"), {"wpml:waypointHeadingMode"});
  expect_children(pm.child("wpml:waypointTurnParam"), {"wpml:waypointTurnMode", "wpml:waypointTurnDampingDist"});
  const double heading = pm.child("wpml:waypointHeadingParam").child("wpml:waypointHeadingAngle").text().as_double();
  EXPECT_GE(heading, -180);
  EXPECT_LE(heading, 180);
  for (pugi::xml_node g : pm.children("wpml:actionGroup")) {
    expect_children(g, {"wpml:actionGroupId", "wpml:actionGroupStartIndex", "wpml:actionGroupEndIndex",
                        "wpml:actionGroupMode", "wpml:actionTrigger", "wpml:action"});
    expect_children(g.child("wpml:actionTrigger"), {"wpml:actionTriggerType"});
    for (pugi::xml_node a : g.children("wpml:action"))
      expect_children(a, {"wpml:actionId", "wpml:actionActuatorFunc", "wpml:actionActuatorFuncParam"});
  }
}

TEST(MissionFormats, KmzHoldsDjiWpmlAndRoundTrips) {
  const Fixture fx(60);
  const std::string dir = temp_dir("kmz");
  const std::string path = dir + "/mission.kmz";
  std::ofstream(path, std::ios::binary) << mission_kmz(fx.plan, *fx.frame, fx.options);
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &err);
  ASSERT_TRUE(z) << "not a zip archive";
  EXPECT_EQ(zip_get_num_entries(z, 0), 2);
  const std::string tmpl = zip_entry(z, "wpmz/template.kml"), lines = zip_entry(z, "wpmz/waylines.wpml");
  zip_close(z);
  for (const std::string* text : {&tmpl, &lines}) {
    const bool is_template = text == &tmpl;
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(text->c_str())) << (is_template ? "template.kml" : "waylines.wpml");
    const pugi::xml_node kml = doc.child("kml");
    EXPECT_STREQ(kml.attribute("xmlns").value(), "http://www.opengis.net/kml/2.2");
    EXPECT_EQ(std::string(kml.attribute("xmlns:wpml").value()).rfind("http://www.dji.com/wpmz/", 0), 0u);
    const pugi::xml_node d = kml.child("Document");
    if (is_template) expect_children(d, {"wpml:createTime", "wpml:updateTime"});
    const pugi::xml_node mc = d.child("wpml:missionConfig");
    expect_children(mc, {"wpml:flyToWaylineMode", "wpml:finishAction", "wpml:exitOnRCLost",
                         "wpml:executeRCLostAction", "wpml:takeOffSecurityHeight",
                         "wpml:globalTransitionalSpeed", "wpml:droneInfo", "wpml:payloadInfo"});
    if (is_template) expect_children(mc, {"wpml:takeOffRefPoint"});
    expect_children(mc.child("wpml:droneInfo"), {"wpml:droneEnumValue", "wpml:droneSubEnumValue"});
    expect_children(mc.child("wpml:payloadInfo"), {"wpml:payloadEnumValue", "wpml:payloadPositionIndex"});
    std::size_t k = 0, photos = 0;
    for (pugi::xml_node folder : d.children("Folder")) {
      expect_children(folder, {"wpml:templateId", "wpml:autoFlightSpeed"});
      if (is_template) {
        expect_children(folder, {"wpml:templateType", "wpml:waylineCoordinateSysParam"});
        EXPECT_STREQ(folder.child_value("wpml:templateType"), "waypoint");
        expect_children(folder.child("wpml:waylineCoordinateSysParam"), {"wpml:coordinateMode", "wpml:heightMode"});
      } else {
        expect_children(folder, {"wpml:waylineId", "wpml:executeHeightMode"});
        EXPECT_STREQ(folder.child_value("wpml:executeHeightMode"), "WGS84");
      }
      const std::vector<Vec3> want = fx.flight_positions(k);
      std::size_t i = 0;
      for (pugi::xml_node pm : folder.children("Placemark")) {
        check_wpml_placemark(pm, is_template);
        EXPECT_EQ(pm.child("wpml:index").text().as_int(), int(i));
        const std::vector<std::string> c = split(pm.child("Point").child_value("coordinates"), ',');
        ASSERT_EQ(c.size(), 2u);
        const double h = pm.child(is_template ? "wpml:ellipsoidHeight" : "wpml:executeHeight").text().as_double();
        ASSERT_LT(i, want.size());
        EXPECT_LT(fx.error_m({std::stod(c[1]), std::stod(c[0]), h}, want[i]), 0.01);
        if (is_template) {
          EXPECT_NEAR(pm.child("wpml:height").text().as_double(), h - fx.plan.takeoff_geo.height, 1e-3);
        }
        photos += pm.child("wpml:actionGroup") ? 1 : 0;
        ++i;
      }
      EXPECT_EQ(i, want.size());
      ++k;
    }
    EXPECT_EQ(k, fx.plan.flights.size());
    EXPECT_EQ(photos, fx.plan.waypoints.size());
  }
}

TEST(MissionFormats, LitchiCsvHeaderAndRoundTrip) {
  const Fixture fx(60);
  EXPECT_EQ(std::string(kLitchiHeader),
            "latitude,longitude,altitude(m),heading(deg),curvesize(m),rotationdir,gimbalmode,"
            "gimbalpitchangle,actiontype1,actionparam1,actiontype2,actionparam2,actiontype3,"
            "actionparam3,actiontype4,actionparam4,actiontype5,actionparam5,actiontype6,actionparam6,"
            "actiontype7,actionparam7,actiontype8,actionparam8,actiontype9,actionparam9,actiontype10,"
            "actionparam10,actiontype11,actionparam11,actiontype12,actionparam12,actiontype13,"
            "actionparam13,actiontype14,actionparam14,actiontype15,actionparam15,altitudemode,"
            "speed(m/s),poi_latitude,poi_longitude,poi_altitude(m),poi_altitudemode,"
            "photo_timeinterval,photo_distinterval");
  const auto files = mission_files(fx.plan, *fx.frame, fx.options, fx.keep_outs);
  std::size_t photos = 0;
  for (std::size_t k = 0; k < fx.plan.flights.size(); ++k) {
    const std::string name = "litchi_" + std::to_string(k + 1) + ".csv";
    const auto it = std::find_if(files.begin(), files.end(), [&](const auto& f) { return f.first == name; });
    ASSERT_NE(it, files.end()) << name;
    std::istringstream in(it->second);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, kLitchiHeader);
    const std::size_t columns = split(line, ',').size();
    const std::vector<Vec3> want = fx.flight_positions(k);
    std::size_t i = 0;
    while (std::getline(in, line)) {
      const std::vector<std::string> c = split(line, ',');
      ASSERT_EQ(c.size(), columns);
      ASSERT_LT(i, want.size());
      const double h = fx.plan.takeoff_geo.height + std::stod(c[2]);  // altitude above take-off
      EXPECT_LT(fx.error_m({std::stod(c[0]), std::stod(c[1]), h}, want[i]), 0.01);
      const double heading = std::stod(c[3]);
      EXPECT_TRUE(heading >= 0 && heading < 360);
      photos += c[8] == "1";
      ++i;
    }
    EXPECT_EQ(i, want.size());
  }
  EXPECT_EQ(photos, fx.plan.waypoints.size());
  EXPECT_TRUE(std::none_of(files.begin(), files.end(), [](const auto& f) { return f.first == "litchi.csv"; }));
  // One flight: litchi.csv alone.
  const Fixture one(60);
  MissionPlan single = one.plan;
  single.flights.resize(1);
  const auto files1 = mission_files(single, *one.frame, one.options, one.keep_outs);
  EXPECT_TRUE(std::any_of(files1.begin(), files1.end(), [](const auto& f) { return f.first == "litchi.csv"; }));
}

TEST(MissionFormats, GeoJsonAndWaypointsCsvRoundTrip) {
  const Fixture fx(60);
  const nlohmann::json g = nlohmann::json::parse(mission_geojson(fx.plan, *fx.frame, fx.keep_outs));
  EXPECT_EQ(g["type"], "FeatureCollection");
  std::size_t photo = 0, paths = 0;
  for (const auto& f : g["features"]) {
    const auto& c = f["geometry"]["coordinates"];
    if (f["properties"]["kind"] == "photo") {
      const Waypoint& w = fx.plan.waypoints[photo++];
      EXPECT_EQ(f["properties"]["label"], w.label);
      EXPECT_LT(fx.error_m({c[1].get<double>(), c[0].get<double>(), c[2].get<double>()}, w.position), 0.01);
    } else if (f["properties"]["kind"] == "takeoff") {
      EXPECT_LT(fx.error_m({c[1].get<double>(), c[0].get<double>(), c[2].get<double>()}, fx.plan.takeoff), 0.01);
    } else if (f["properties"]["kind"] == "path") {
      EXPECT_EQ(c.size(), fx.plan.flights[paths++].points.size() + 2);
    }
  }
  EXPECT_EQ(photo, fx.plan.waypoints.size());
  EXPECT_EQ(paths, fx.plan.flights.size());
  std::istringstream in(waypoints_csv(fx.plan));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line, ',');
  auto col = [&](const char* name) { return std::size_t(std::find(header.begin(), header.end(), name) - header.begin()); };
  std::size_t i = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> c = split(line, ',');
    const Waypoint& w = fx.plan.waypoints[i++];
    const Geodetic geo{std::stod(c[col("latitude")]), std::stod(c[col("longitude")]),
                       std::stod(c[col("ellipsoidal_height")])};
    EXPECT_LT(fx.error_m(geo, w.position), 0.01);
    const Vec3 xyz(std::stod(c[col("x")]), std::stod(c[col("y")]), std::stod(c[col("z")]));
    EXPECT_LT((xyz - w.position).norm(), 1e-5);
  }
  EXPECT_EQ(i, fx.plan.waypoints.size());
}

}  // namespace
}  // namespace meshnbv::test
