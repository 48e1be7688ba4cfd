// Where the drone may be (docs/missions.md): the constraints of
// MissionOptions that hold for every point of the flight path, checked on
// waypoints and on every straight leg between two. Keep-out volumes are
// polygons (GeoJSON, WGS84 longitude/latitude, with a floor and a ceiling
// in metres above take-off) or boxes in scene coordinates.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "meshnbv/mission/georef.h"
#include "meshnbv/mission_options.h"
#include "meshnbv/raycaster.h"

namespace meshnbv::mission {

struct KeepOutPolygon {
  std::string name;
  std::vector<Vec2> lonlat;  // the ring, not repeated at the end
  double floor = -std::numeric_limits<double>::infinity();    // metres above take-off
  double ceiling = std::numeric_limits<double>::infinity();
};

struct KeepOutBox {
  std::string name;
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();  // scene coordinates
};

struct KeepOuts {
  std::vector<KeepOutPolygon> polygons;
  std::vector<KeepOutBox> boxes;
};

// A GeoJSON FeatureCollection (or one Feature) of Polygons; properties
// "name", "floor", "ceiling" (metres above take-off, default unbounded).
// Error (one line, naming the file and feature) for other geometries,
// holes, fewer than 3 distinct corners, non-finite or out-of-range
// coordinates, floor >= ceiling, or a ring that intersects itself.
KeepOuts parse_keep_out_geojson(const std::string& text, const std::string& name);
KeepOuts read_keep_out_geojson(const std::string& path);
// "xmin,ymin,zmin,xmax,ymax,zmax" (scene coordinates); Error otherwise.
KeepOutBox parse_keep_out_box(const std::string& text);
// Whether a closed ring has two non-adjacent edges that touch or cross.
bool ring_self_intersects(const std::vector<Vec2>& ring);

class Airspace {
 public:
  // `takeoff` in scene coordinates; the options' distances are converted
  // to scene units through the frame.
  Airspace(const RayCaster& caster, const GeoFrame& frame, const Vec3& takeoff,
           const MissionOptions& options, const KeepOuts& keep_outs);

  double height(const Vec3& p) const;  // metres above take-off
  // Why the drone may not be at `p`, or empty.
  std::string point_problem(const Vec3& p) const;
  // Why the straight leg from `a` to `b` may not be flown, or empty. A
  // vertical leg at the take-off point (take-off, landing) is exempt from
  // the minimum altitude and the mesh distance, not from the rest.
  std::string leg_problem(const Vec3& a, const Vec3& b, bool takeoff_leg = false) const;
  // Distance (scene units) below which a point is too close to the mesh.
  double mesh_clearance() const { return clearance_; }
  const Vec3& takeoff() const { return takeoff_; }
  const GeoFrame& frame() const { return frame_; }
  const MissionOptions& options() const { return options_; }
  const RayCaster& caster() const { return caster_; }

 private:
  std::string keep_out_problem(const Vec3& a, const Vec3& b) const;
  std::string mesh_problem(const Vec3& a, const Vec3& b) const;

  const RayCaster& caster_;
  const GeoFrame& frame_;
  Vec3 takeoff_;
  double takeoff_height_;
  MissionOptions options_;
  KeepOuts keep_outs_;
  std::vector<std::vector<Vec2>> rings_crs_;  // the polygons in CRS x, y
  double clearance_;
};

}  // namespace meshnbv::mission
