// The visual report of a run: report.html (pictures embedded) plus the PNGs
// it shows, and its interactive 3-D view in viewer/ (the bundled viewer and
// the data it shows, loaded by the page as classic scripts: it works
// offline from file://).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "meshnbv/display_mesh.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"

namespace meshnbv {

// The drone mission of the suggestions (meshnbv::mission, planned by the
// caller): its top view and flights, or why there is none.
struct ReportFlight {
  int photos = 0;
  double length_m = 0, minutes = 0;
  int detours = 0;
};
struct ReportMission {
  std::string unavailable;   // why no mission was planned (shown); empty when planned
  std::string georef;        // the georeference's source
  std::string svg;           // the flights from above (mission.svg), inlined
  std::string takeoff;       // text, e.g. "46.5000000 N, 7.2500000 E"
  std::vector<ReportFlight> flights;
  std::vector<std::string> notes;  // moved, dropped, detour, with the reason
  std::string folder;        // where the mission files are, relative to the report
};

struct ReportInputs {
  const Scene* scene = nullptr;
  const PriResult* pri = nullptr;
  PriOptions pri_options;
  const SuggestResult* suggestions = nullptr;
  SuggestOptions suggest_options;
  std::string scene_path;
  std::vector<std::pair<std::string, double>> timings;      // step, seconds
  std::vector<std::pair<std::string, std::string>> files;   // file name, what it is
  int image_width = 960, image_height = 720;                // overview pictures
  int suggestion_views = 3;                                 // pictures from the top suggestions
  std::size_t display_faces = kDefaultDisplayFaces;         // 3-D view: decimated above this many faces
  std::size_t interaction_faces = kDefaultInteractionFaces; // 3-D view while the camera moves: a coarser copy
                                                            // of at most this many faces (none when the
                                                            // display mesh has no more)
  const ReportMission* mission = nullptr;                   // optional section
};

struct ReportFiles {
  std::string html;
  std::vector<std::string> pictures;
};

// Renders the pictures with our renderer and writes them, the 3-D view's
// files (viewer/) and report.html into `folder`. Progress stage "report".
ReportFiles write_report(const ReportInputs& inputs, const std::string& folder,
                         const ProgressCallback& progress = {});

}  // namespace meshnbv
