// meshnbv mission: drone missions that take the suggested photos
// (meshnbv::mission, docs/missions.md).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "meshnbv/energy.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/mission/suggestions.h"
#include "meshnbv/mission/writers.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/options.h"
#include "meshnbv/raycaster.h"

namespace meshnbv::cli {
namespace {

namespace fs = std::filesystem;
using namespace meshnbv::mission;

struct MissionArgs {
  SceneInput input;
  MissionOptions options;
  OptionFlags flags;
  std::string suggestions, out, georef, takeoff, takeoff_wgs84, keep_out;
  std::vector<std::string> boxes;
  bool overwrite = false;
};

std::vector<double> numbers(const std::string& text, const std::string& what, std::size_t min,
                            std::size_t max) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) v.push_back(io::parse_double(item, what, -1, "coordinate"));
  if (v.size() < min || v.size() > max) throw Error(what + " takes " + std::to_string(min) +
                                                    (min == max ? "" : " or " + std::to_string(max)) +
                                                    " comma-separated numbers, got '" + text + "'");
  return v;
}

Georeference scene_georef(const MissionArgs& a, const Scene& scene) {
  if (!a.georef.empty()) return read_georef_file(a.georef);
  const std::vector<GpsFix> fixes = gps_fixes(scene);
  if (fixes.empty())
    throw Error("no georeference: the scene's photos carry no EXIF GPS and no --georef FILE was given");
  return fit_georef(fixes);
}

// --takeoff, --takeoff-wgs84, or the ground below the first photo: the
// lowest mesh point along the vertical there (the mesh's lowest height).
Vec3 takeoff_point(const MissionArgs& a, const Scene& scene, const GeoFrame& frame) {
  if (!a.takeoff.empty()) {
    const std::vector<double> v = numbers(a.takeoff, "--takeoff", 3, 3);
    return Vec3(v[0], v[1], v[2]);
  }
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : scene.mesh.vertices) lowest = std::min(lowest, frame.up().dot(v));
  if (!a.takeoff_wgs84.empty()) {
    const std::vector<double> v = numbers(a.takeoff_wgs84, "--takeoff-wgs84", 2, 3);
    const Vec3 p = frame.from_wgs84({v[0], v[1], v.size() == 3 ? v[2] : 0.0});
    return v.size() == 3 ? p : Vec3(p + (lowest - frame.up().dot(p)) * frame.up());
  }
  for (const View& view : scene.views)
    if (view.has_image()) {
      const Vec3 c = view.camera.center();
      return c + (lowest - frame.up().dot(c)) * frame.up();
    }
  throw Error("no take-off point: give --takeoff x,y,z or --takeoff-wgs84 lat,lon");
}

// The next-view energy of a moved suggestion, with the suggestions' own
// options and worst regions, against the scene's used views.
Rescore energy_rescore(const Scene& scene, const RayCaster& caster, const SuggestionsFile& s,
                       std::vector<std::unique_ptr<EnergyEvaluator>>* keep) {
  SuggestOptions so;
  if (!s.options.empty()) parse_options_json(s.options, suggest_option_table(), &so);
  std::vector<Vec3> existing;
  for (const View& v : scene.views)
    if (v.has_image() && v.used) existing.push_back(v.camera.center());
  for (const std::vector<int>& faces : s.region_faces) {
    std::vector<float> pri(scene.mesh.faces.size(), std::nanf(""));
    for (int f : faces)
      if (std::size_t(f) >= pri.size()) throw Error("the suggestions' regions do not fit the scene's mesh");
      else pri[std::size_t(f)] = 1.0f;
    if (faces.empty()) {
      keep->push_back(nullptr);
      continue;
    }
    const WorstRegion region = worst_region(scene.mesh, pri, int(faces.size()));
    keep->push_back(std::make_unique<EnergyEvaluator>(scene.mesh, caster, region, existing, so.energy));
  }
  return [keep](const PinholeCamera& c, int region) {
    if (region < 0 || std::size_t(region) >= keep->size() || !(*keep)[std::size_t(region)])
      return std::numeric_limits<double>::quiet_NaN();
    return (*keep)[std::size_t(region)]->evaluate(c).total;
  };
}

void check_outputs(const MissionArgs& a) {
  io::check_can_write_folder(a.out);
  for (const char* f : {"mission.kml", "mission.kmz", "litchi.csv", "mission.geojson", "waypoints.csv",
                        "mission.json", "mission.svg"})
    io::check_can_write((fs::path(a.out) / f).string(), a.overwrite);
  if (!a.overwrite && fs::is_directory(a.out))
    for (const auto& e : fs::directory_iterator(a.out))
      if (e.path().filename().string().rfind("litchi_", 0) == 0)
        throw Error("output " + e.path().string() + " exists (use --overwrite)");
}

void run_mission(MissionArgs& a) {
  a.flags.apply();
  a.options.check();
  check_outputs(a);
  Scene scene = a.input.read();
  if (scene.mesh.faces.empty()) throw Error("the scene has no mesh (give --mesh)");
  const SuggestionsFile sug = read_suggestions_file(a.suggestions);
  KeepOuts keep_outs;
  if (!a.keep_out.empty()) keep_outs = read_keep_out_geojson(a.keep_out);
  for (const std::string& b : a.boxes) keep_outs.boxes.push_back(parse_keep_out_box(b));
  const GeoFrame frame(scene_georef(a, scene));
  const RayCaster caster(scene.mesh);
  const Airspace air(caster, frame, takeoff_point(a, scene, frame), a.options, keep_outs);
  auto evaluators = std::make_shared<std::vector<std::unique_ptr<EnergyEvaluator>>>();
  const Rescore rescore = energy_rescore(scene, caster, sug, evaluators.get());
  const MissionPlan plan = plan_mission(sug.suggestions, air, rescore);
  const auto files = mission_files(plan, frame, a.options, keep_outs, &scene.mesh);  // all in memory first
  fs::create_directories(a.out);
  for (const auto& [name, content] : files)
    io::write_atomically((fs::path(a.out) / name).string(), [&](std::ostream& o) { o << content; },
                         a.overwrite, true);
  const Georeference& g = frame.georef();
  std::cout << "georeference: " << g.source;
  if (!g.residuals.empty()) std::cout << ", rms residual " << g.rms_residual() << " m";
  std::cout << "\n";
  for (const Note& n : plan.notes) std::cout << n.label << ": " << n.action << " (" << n.reason << ")\n";
  for (std::size_t k = 0; k < plan.flights.size(); ++k)
    std::cout << "flight " << k + 1 << ": " << plan.flights[k].waypoints.size() << " photos, "
              << plan.flights[k].length_m << " m, " << plan.flights[k].minutes << " min\n";
  std::cout << plan.waypoints.size() << " of " << sug.suggestions.size() << " suggestions in "
            << plan.flights.size() << " flight(s), " << plan.total_minutes() << " min\nmission: "
            << a.out << "\n";
}

}  // namespace

void add_mission_command(CLI::App& app) {
  auto a = std::make_shared<MissionArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mission", "Drone missions that take the suggested photos: georeferenced, within altitude, "
                 "keep-out, mesh-distance, gimbal, GSD and battery limits (KML, DJI WPML KMZ, "
                 "Litchi CSV, GeoJSON, CSV)");
  a->input.add_to(cmd);
  cmd->add_option("--suggestions", a->suggestions, "Suggestions JSON (meshnbv suggest / run)")->required();
  cmd->add_option("--out", a->out, "Output folder")->required();
  cmd->add_option("--georef", a->georef,
                  "Georeference JSON {\"crs\": \"EPSG:32632\", \"transform\": [16 numbers, row-major "
                  "scene -> CRS]}; otherwise fitted to the photos' EXIF GPS");
  cmd->add_option("--takeoff", a->takeoff, "Take-off point x,y,z in scene coordinates");
  cmd->add_option("--takeoff-wgs84", a->takeoff_wgs84,
                  "Take-off point lat,lon[,ellipsoidal height] (without height: on the mesh's lowest level)");
  cmd->add_option("--keep-out", a->keep_out,
                  "Keep-out polygons: GeoJSON with properties floor, ceiling (metres above take-off)");
  cmd->add_option("--keep-out-box", a->boxes, "Keep-out box xmin,ymin,zmin,xmax,ymax,zmax (scene "
                                             "coordinates); repeatable");
  a->flags.add(cmd, mission_option_table(), &a->options);
  cmd->add_flag("--overwrite", a->overwrite, "Replace existing output files");
  cmd->callback([a]() { run_mission(*a); });
}

}  // namespace meshnbv::cli
