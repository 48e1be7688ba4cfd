// The files of the report's 3-D view: viewer/meshnbv_viewer.js (the bundled
// viewer) and viewer/report_data.js (the display mesh, per-face values,
// cameras, suggestions and regions as one global, binary arrays in base64),
// both loaded by report.html as classic scripts, so that the page works from
// file:// with no request. Internal to meshnbv::report.
#pragma once

#include <string>
#include <utility>

#include "meshnbv/report.h"

namespace meshnbv::report_detail {

struct ViewerFiles {
  std::size_t original_faces = 0, display_faces = 0;
  std::size_t interaction_faces = 0;  // the coarser mesh drawn while the camera moves; 0: none
  bool decimated = false;
  std::string folder = "viewer";  // relative to the report
};

// `range`: the colour scale's ends (5th and 95th percentiles of PRI).
ViewerFiles write_viewer(const ReportInputs& in, const std::string& report_folder,
                         std::pair<double, double> range);

}  // namespace meshnbv::report_detail
