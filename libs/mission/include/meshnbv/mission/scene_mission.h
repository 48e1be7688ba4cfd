// A mission for a scene's suggestions from what a user has (docs/missions.md):
// the georeference from --georef, the scene's own CRS or its photos' EXIF
// GPS; the take-off point; the suggestions re-scored with their own energy
// when moved; the files in memory. What `meshnbv mission`, the mission
// section of `meshnbv run` and vtkMeshNBVMissionWriter share.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshnbv/mission/plan.h"
#include "meshnbv/mission/suggestions.h"
#include "meshnbv/scene.h"

namespace meshnbv::mission {

struct MissionRequest {
  // --georef: a file, "ecef" or "enu:LAT,LON,H"; empty: the scene's own CRS
  // (Scene::crs), else the photos' EXIF GPS.
  std::string georef;
  std::optional<Vec3> takeoff;            // scene coordinates
  std::optional<Geodetic> takeoff_wgs84;  // else this (height: see below)
  bool takeoff_wgs84_has_height = true;   // false: on the mesh's lowest level there
  KeepOuts keep_outs;
  MissionOptions options;
};

struct SceneMission {
  std::unique_ptr<GeoFrame> frame;
  MissionPlan plan;
  std::vector<std::pair<std::string, std::string>> files;  // mission_files, SVG included
};

// The take-off point from the text of --takeoff ("x,y,z", scene) or else
// --takeoff-wgs84 ("lat,lon[,h]"); both empty: none (the default rule).
// Error (one line, naming the flag) for anything else.
void set_takeoff(const std::string& takeoff, const std::string& takeoff_wgs84, MissionRequest* request);

// The georeference of a scene by the request's rule, localized
// (localize_georef) over its camera centres and mesh. Error (one line) when
// there is none: no --georef, no CRS in the source, no photo with GPS.
Georeference scene_georeference(const Scene& scene, const std::string& georef);

// The take-off point: the request's, else the ground below the scene's
// first photo (the mesh's lowest level along the vertical there).
Vec3 takeoff_point(const MissionRequest& request, const Scene& scene, const GeoFrame& frame);

// Plans the mission (plan_mission), moved suggestions re-scored with the
// suggestions' energy against the scene's used views; Error when the scene
// has no mesh, the suggestions do not fit it, or nothing can be flown.
SceneMission plan_scene_mission(const Scene& scene, const SuggestionsFile& suggestions,
                                const MissionRequest& request);

// The names mission_files may write (litchi_<k>.csv aside), for checks
// before any work.
const std::vector<std::string>& mission_file_names();
// Throws Error when `dir` cannot take the files (an existing one without
// `overwrite`, litchi_<k>.csv included; an unwritable folder).
void check_mission_outputs(const std::string& dir, bool overwrite);
// Writes the files into `dir` (created), each atomically.
void write_mission_files(const SceneMission& mission, const std::string& dir, bool overwrite);

}  // namespace meshnbv::mission
