// Options of drone missions (meshnbv::mission, docs/missions.md): the
// constraints every waypoint and every straight leg between two is checked
// against, and the battery model that splits the route into flights. Plain
// data in the core so that its option table sits with the others
// (options.h: mission_option_table()); distances in metres, angles in
// degrees, altitudes above the take-off point.
#pragma once

#include <string>

namespace meshnbv {

struct MissionOptions {
  double min_altitude = 2;         // metres above take-off, waypoints and legs
  double max_altitude = 120;       // metres above take-off
  double min_mesh_distance = 2;    // metres from the mesh, waypoints and legs
  double gimbal_pitch_min = -90;   // degrees, -90 = straight down
  double gimbal_pitch_max = 0;     // degrees, 0 = horizontal
  double target_gsd = 0;           // cm per pixel at the look-at point; 0 = no cap
  int max_waypoints = 99;          // photos per flight (Litchi's limit)
  double speed = 5;                // m/s, horizontal and vertical
  double time_per_photo = 3;       // seconds at each waypoint (turn, gimbal, shot)
  double battery_minutes = 15;     // usable flight time per battery
  std::string infeasible = "move"; // move | drop: what happens to a suggestion that breaks a constraint

  // The table's ranges and min_altitude < max_altitude,
  // gimbal_pitch_min < gimbal_pitch_max; throws Error.
  void check() const;
};

}  // namespace meshnbv
