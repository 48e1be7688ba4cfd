// The points of a flight as the writers need them (private to the writers).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "meshnbv/mission/plan.h"

namespace meshnbv::mission {

struct OutPoint {
  Geodetic geo;
  double height = 0;    // metres above take-off
  double heading = 0;   // of the photo, or of the next photo (path points)
  double pitch = 0;
  int waypoint = -1;    // index into plan.waypoints, -1 = path point
};

std::vector<OutPoint> flight_points(const MissionPlan& plan, std::size_t flight, const GeoFrame& frame);

// Fixed-point text: 10 decimals for degrees (0.01 mm), 4 for metres.
inline std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

}  // namespace meshnbv::mission
