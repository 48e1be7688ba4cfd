// The files of a mission (docs/missions.md), built in memory so that an
// error leaves nothing written:
//   mission.kml      waypoints, path, camera heading and tilt per photo (any GIS, Google Earth)
//   mission.kmz      DJI WPML (wpmz/template.kml + wpmz/waylines.wpml; Pilot 2, FlightHub 2)
//   litchi.csv       Litchi mission (litchi_<k>.csv per flight when split)
//   mission.geojson  photos, paths, take-off point, keep-out polygons
//   waypoints.csv    scene and WGS84 coordinates of every photo
//   mission.json     summary: flights, moved and dropped suggestions and why
//   mission.svg      the flights from above over the mesh (up-facing faces),
//                    keep-out volumes, take-off point, minutes per flight
// Every flight's points run from the climb's top above the take-off point
// back to it, photo waypoints and path points (detour corners) alike, so
// that an app flying straight between them flies the checked path.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "meshnbv/mission/plan.h"

namespace meshnbv::mission {

// The exact header of Litchi's mission CSV (metric).
extern const char* const kLitchiHeader;

std::string mission_kml(const MissionPlan& plan, const GeoFrame& frame);
// The KMZ archive's bytes.
std::string mission_kmz(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& options);
std::string wpml_template_kml(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& options);
std::string wpml_waylines(const MissionPlan& plan, const GeoFrame& frame, const MissionOptions& options);
std::string litchi_csv(const MissionPlan& plan, std::size_t flight, const GeoFrame& frame,
                       const MissionOptions& options);
std::string mission_geojson(const MissionPlan& plan, const GeoFrame& frame, const KeepOuts& keep_outs);
std::string waypoints_csv(const MissionPlan& plan);
std::string mission_summary_json(const MissionPlan& plan, const GeoFrame& frame,
                                 const MissionOptions& options);

std::string mission_svg(const MissionPlan& plan, const GeoFrame& frame, const TriangleMesh& mesh,
                        const KeepOuts& keep_outs);

// Every file above as (name, content); the SVG only with a mesh.
std::vector<std::pair<std::string, std::string>> mission_files(const MissionPlan& plan,
                                                               const GeoFrame& frame,
                                                               const MissionOptions& options,
                                                               const KeepOuts& keep_outs,
                                                               const TriangleMesh* mesh = nullptr);

}  // namespace meshnbv::mission
