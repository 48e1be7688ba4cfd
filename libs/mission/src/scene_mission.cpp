// A scene's mission from the sources a user has (scene_mission.h).
#include "meshnbv/mission/scene_mission.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "meshnbv/energy.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/mission/writers.h"
#include "meshnbv/options.h"
#include "meshnbv/planner.h"
#include "meshnbv/raycaster.h"
#include "coordinates_text.h"

namespace meshnbv::mission {
namespace {

namespace fs = std::filesystem;

// The points a curved frame is fitted over: every camera centre and up to
// 4096 mesh vertices spread over the vertex list.
std::vector<Vec3> scene_points(const Scene& scene) {
  std::vector<Vec3> points;
  for (const View& v : scene.views) points.push_back(v.camera.center());
  const std::size_t n = scene.mesh.vertices.size();
  const std::size_t step = std::max<std::size_t>(1, n / 4096);
  for (std::size_t i = 0; i < n; i += step) points.push_back(scene.mesh.vertices[i]);
  return points;
}

// The next-view energy of a moved suggestion, with the suggestions' own
// options and worst regions, against the scene's used views.
struct Rescorer {
  std::vector<std::unique_ptr<EnergyEvaluator>> evaluators;  // per region; null when empty

  Rescorer(const Scene& scene, const RayCaster& caster, const SuggestionsFile& s) {
    SuggestOptions so;
    if (!s.options.empty()) parse_options_json(s.options, suggest_option_table(), &so);
    std::vector<Vec3> existing;
    for (const View& v : scene.views)
      if (v.has_image() && v.used) existing.push_back(v.camera.center());
    for (const std::vector<int>& faces : s.region_faces) {
      if (faces.empty()) {
        evaluators.push_back(nullptr);
        continue;
      }
      std::vector<float> pri(scene.mesh.faces.size(), std::nanf(""));
      for (int f : faces) {
        if (f < 0 || std::size_t(f) >= pri.size())
          throw Error("the suggestions' regions do not fit the scene's mesh (face " + std::to_string(f) +
                      " of " + std::to_string(pri.size()) + ")");
        pri[std::size_t(f)] = 1.0f;
      }
      const WorstRegion region = worst_region(scene.mesh, pri, int(faces.size()));
      evaluators.push_back(std::make_unique<EnergyEvaluator>(scene.mesh, caster, region, existing, so.energy));
    }
  }
  double operator()(const PinholeCamera& c, int region) const {
    if (region < 0 || std::size_t(region) >= evaluators.size() || !evaluators[std::size_t(region)])
      return std::numeric_limits<double>::quiet_NaN();
    return evaluators[std::size_t(region)]->evaluate(c).total;
  }
};

std::vector<double> numbers(const std::string& text, const std::string& what, std::size_t min,
                            std::size_t max) {
  const std::vector<double> v = comma_numbers(text, what);
  if (v.size() < min || v.size() > max)
    throw Error(what + " takes " + std::to_string(min) + (min == max ? "" : " or " + std::to_string(max)) +
                " comma-separated numbers, got '" + text + "'");
  return v;
}

}  // namespace

void set_takeoff(const std::string& takeoff, const std::string& takeoff_wgs84, MissionRequest* r) {
  r->takeoff.reset();
  r->takeoff_wgs84.reset();
  if (!takeoff.empty()) {
    const std::vector<double> v = numbers(takeoff, "--takeoff", 3, 3);
    r->takeoff = Vec3(v[0], v[1], v[2]);
  } else if (!takeoff_wgs84.empty()) {
    const std::vector<double> v = numbers(takeoff_wgs84, "--takeoff-wgs84", 2, 3);
    if (!(std::abs(v[0]) <= 90) || !(std::abs(v[1]) <= 180))
      throw Error("--takeoff-wgs84 must be a latitude in [-90, 90] and a longitude in [-180, 180], got '" +
                  takeoff_wgs84 + "'");
    r->takeoff_wgs84 = Geodetic{v[0], v[1], v.size() == 3 ? v[2] : 0.0};
    r->takeoff_wgs84_has_height = v.size() == 3;
  }
}

Georeference scene_georeference(const Scene& scene, const std::string& georef) {
  Georeference g;
  if (!georef.empty()) {
    g = parse_georef_argument(georef);
  } else if (auto own = scene_crs_georef(scene)) {
    g = *own;
  } else {
    const std::vector<GpsFix> fixes = gps_fixes(scene);
    if (fixes.empty())
      throw Error("no georeference: the scene's source states no CRS, its photos carry no EXIF GPS, "
                  "and no --georef (FILE, ecef or enu:LAT,LON,H) was given");
    return fit_georef(fixes);
  }
  return localize_georef(g, scene_points(scene));
}

Vec3 takeoff_point(const MissionRequest& r, const Scene& scene, const GeoFrame& frame) {
  if (r.takeoff) return *r.takeoff;
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : scene.mesh.vertices) lowest = std::min(lowest, frame.up().dot(v));
  auto on_ground = [&](const Vec3& p) { return Vec3(p + (lowest - frame.up().dot(p)) * frame.up()); };
  if (r.takeoff_wgs84) {
    const Vec3 p = frame.from_wgs84(*r.takeoff_wgs84);
    return r.takeoff_wgs84_has_height ? p : on_ground(p);
  }
  for (const View& view : scene.views)
    if (view.has_image()) return on_ground(view.camera.center());
  throw Error("no take-off point: give --takeoff x,y,z or --takeoff-wgs84 lat,lon");
}

SceneMission plan_scene_mission(const Scene& scene, const SuggestionsFile& suggestions,
                                const MissionRequest& request) {
  request.options.check();
  if (scene.mesh.faces.empty()) throw Error("the scene has no mesh (give --mesh)");
  SceneMission m;
  m.frame = std::make_unique<GeoFrame>(scene_georeference(scene, request.georef));
  const RayCaster caster(scene.mesh);
  const Airspace air(caster, *m.frame, takeoff_point(request, scene, *m.frame), request.options,
                     request.keep_outs);
  const auto rescorer = std::make_shared<Rescorer>(scene, caster, suggestions);
  m.plan = plan_mission(suggestions.suggestions, air,
                        [rescorer](const PinholeCamera& c, int region) { return (*rescorer)(c, region); });
  m.files = mission_files(m.plan, *m.frame, request.options, request.keep_outs, &scene.mesh);
  return m;
}

const std::vector<std::string>& mission_file_names() {
  static const std::vector<std::string> names = {"mission.kml",     "mission.kmz",   "litchi.csv",
                                                 "mission.geojson", "waypoints.csv", "mission.json",
                                                 "mission.svg"};
  return names;
}

void check_mission_outputs(const std::string& dir, bool overwrite) {
  io::check_can_write_folder(dir);
  for (const std::string& f : mission_file_names()) io::check_can_write((fs::path(dir) / f).string(), overwrite);
  std::error_code ec;
  if (!overwrite && fs::is_directory(dir, ec))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().rfind("litchi_", 0) == 0)
        throw Error("output " + e.path().string() + " exists (use --overwrite)");
}

void write_mission_files(const SceneMission& mission, const std::string& dir, bool overwrite) {
  fs::create_directories(dir);
  for (const auto& [name, content] : mission.files)
    io::write_atomically((fs::path(dir) / name).string(), [&](std::ostream& o) { o << content; }, overwrite,
                         true);
}

}  // namespace meshnbv::mission
