// Drone missions for the suggested views (docs/missions.md): each
// suggestion checked against the constraints (moved to the nearest feasible
// pose and re-scored, or dropped, with the reason), ordered into a short
// route from the take-off point (nearest neighbour, then 2-opt), legs that
// break a constraint detoured over the obstacle or their waypoint dropped,
// and the route split into flights that fit the battery and the waypoint
// limit. Every flight climbs vertically from the take-off point to the
// climb height, flies its legs, comes back above the take-off point and
// lands vertically.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/mission/airspace.h"

namespace meshnbv::mission {

// A suggestion as the mission sees it.
struct MissionInput {
  std::string label;
  int rank = 0;
  int region = 0;
  PinholeCamera camera;
  Vec3 look_at = Vec3::Zero();
  double energy = std::numeric_limits<double>::quiet_NaN();
};

struct Waypoint {
  std::string label;
  int rank = 0;
  Vec3 position = Vec3::Zero();  // scene
  Vec3 look_at = Vec3::Zero();
  Geodetic geo;
  double height = 0;             // metres above take-off
  double heading = 0;            // degrees clockwise from true north
  double pitch = 0;              // gimbal pitch, degrees (-90 = down)
  int flight = -1, order = -1;   // which flight, and its place in it
  bool moved = false;
  double moved_by = 0;           // metres
  double energy = std::numeric_limits<double>::quiet_NaN();           // after a move: re-scored
  double original_energy = std::numeric_limits<double>::quiet_NaN();
};

// A point of a flight's path: a photo (waypoint index) or a path point
// (the climb's top, a detour corner), waypoint = -1.
struct PathPoint {
  Vec3 position = Vec3::Zero();
  int waypoint = -1;
};

struct Flight {
  std::vector<PathPoint> points;  // from the climb's top back to it
  std::vector<int> waypoints;     // photo waypoints in flight order
  double length_m = 0;            // including the climb and the descent
  double minutes = 0;             // length / speed + photos x time per photo
  int detours = 0;
};

struct Note {
  std::string label;
  std::string action;  // moved | dropped | detour
  std::string reason;
};

struct MissionPlan {
  Vec3 takeoff = Vec3::Zero();    // scene
  Vec3 climb_top = Vec3::Zero();
  double climb_height = 0;        // metres above take-off
  Geodetic takeoff_geo;
  std::vector<Waypoint> waypoints;  // the ones flown
  std::vector<Flight> flights;
  std::vector<Note> notes;
  double total_minutes() const;
};

// Re-scores a moved camera (the next-view energy of its region); optional.
using Rescore = std::function<double(const PinholeCamera& camera, int region)>;

// Throws Error when no climb above the take-off point is possible or no
// suggestion can be flown within the constraints (nothing is planned).
MissionPlan plan_mission(const std::vector<MissionInput>& suggestions, const Airspace& airspace,
                         const Rescore& rescore = {});

// Routing (closed tours from `start` back to it, over `points`).
double tour_length(const Vec3& start, const std::vector<Vec3>& points, const std::vector<int>& order);
std::vector<int> nearest_neighbour_order(const Vec3& start, const std::vector<Vec3>& points);
// 2-opt from `order` until no reversal shortens the tour (never longer).
std::vector<int> two_opt(const Vec3& start, const std::vector<Vec3>& points, std::vector<int> order);
// two_opt(nearest_neighbour_order).
std::vector<int> route_order(const Vec3& start, const std::vector<Vec3>& points);

}  // namespace meshnbv::mission
