// meshnbv mission: drone missions that take the suggested photos
// (meshnbv::mission, docs/missions.md).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "meshnbv/error.h"
#include "meshnbv/io/file_util.h"
#include "meshnbv/mission/scene_mission.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/options.h"

namespace meshnbv::cli {

using namespace meshnbv::mission;

namespace {

struct MissionArgs {
  SceneInput input;
  OptionFlags flags;
  MissionFlags mission;
  std::string suggestions, out;
  bool overwrite = false;
};

void run_mission(MissionArgs& a) {
  a.flags.apply();
  a.mission.options.check();
  check_mission_outputs(a.out, a.overwrite);
  const Scene scene = a.input.read();
  const SuggestionsFile sug = read_suggestions_file(a.suggestions);
  const SceneMission m = plan_scene_mission(scene, sug, a.mission.request());  // all in memory first
  write_mission_files(m, a.out, a.overwrite);
  const MissionPlan& plan = m.plan;
  const Georeference& g = m.frame->georef();
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

void MissionFlags::add_to(CLI::App* cmd, OptionFlags* flags) {
  cmd->add_option("--georef", georef,
                  "Georeference: a JSON file {\"crs\": \"EPSG:32632\", \"transform\": [16 numbers, row-major "
                  "scene -> CRS]}, 'ecef' (scene coordinates geocentric, EPSG:4978) or 'enu:LAT,LON,H' "
                  "(east-north-up from that origin); otherwise the scene's own CRS, else its photos' EXIF GPS");
  cmd->add_option("--takeoff", takeoff, "Take-off point x,y,z in scene coordinates");
  cmd->add_option("--takeoff-wgs84", takeoff_wgs84,
                  "Take-off point lat,lon[,ellipsoidal height] (without height: on the mesh's lowest level)");
  cmd->add_option("--keep-out", keep_out,
                  "Keep-out polygons: GeoJSON with properties floor, ceiling (metres above take-off)");
  cmd->add_option("--keep-out-box", boxes, "Keep-out box xmin,ymin,zmin,xmax,ymax,zmax (scene "
                                           "coordinates); repeatable");
  flags->add(cmd, mission_option_table(), &options);
}

MissionRequest MissionFlags::request() const {
  MissionRequest r;
  r.georef = georef;
  r.options = options;
  if (!keep_out.empty()) r.keep_outs = read_keep_out_geojson(keep_out);
  for (const std::string& b : boxes) r.keep_outs.boxes.push_back(parse_keep_out_box(b));
  set_takeoff(takeoff, takeoff_wgs84, &r);
  return r;
}

void add_mission_command(CLI::App& app) {
  auto a = std::make_shared<MissionArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mission", "Drone missions that take the suggested photos: georeferenced, within altitude, "
                 "keep-out, mesh-distance, gimbal, GSD and battery limits (KML, DJI WPML KMZ, "
                 "Litchi CSV, GeoJSON, CSV)");
  a->input.add_to(cmd);
  cmd->add_option("--suggestions", a->suggestions, "Suggestions JSON (meshnbv suggest / run)")->required();
  cmd->add_option("--out", a->out, "Output folder")->required();
  a->mission.add_to(cmd, &a->flags);
  cmd->add_flag("--overwrite", a->overwrite, "Replace existing output files");
  cmd->callback([a]() { run_mission(*a); });
}

}  // namespace meshnbv::cli
