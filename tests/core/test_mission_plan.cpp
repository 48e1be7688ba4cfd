// Drone missions (meshnbv::mission, plan.h, airspace.h): property tests on
// random scenes and constraints, checked by dense sampling independent of
// the planner's own checks: no waypoint or leg violates a constraint,
// every flight fits the battery and the waypoint limit, and the route is
// never longer than the nearest-neighbour order. Keep-out input errors.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "meshnbv/error.h"
#include "meshnbv/mission/plan.h"
#include "meshnbv/raycaster.h"
#include "test_geometry.h"
#include "test_util.h"

namespace meshnbv::test {
namespace {

using namespace meshnbv::mission;

void add_box(TriangleMesh* m, const Vec3& lo, const Vec3& hi) {
  const int b = int(m->vertices.size());
  for (int i = 0; i < 8; ++i)
    m->vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f) m->faces.push_back({b + t[0], b + t[1], b + t[2]});
}

bool in_ring(const std::vector<Vec2>& r, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    if ((r[i].y() > p.y()) != (r[j].y() > p.y()) &&
        p.x() < (r[j].x() - r[i].x()) * (p.y() - r[i].y()) / (r[j].y() - r[i].y()) + r[i].x())
      in = !in;
  return in;
}

struct World {
  TriangleMesh mesh;
  Georeference georef;
  KeepOuts keep_outs;
  MissionOptions options;
  Vec3 takeoff;
  std::vector<MissionInput> suggestions;
};

// Boxes ("buildings") standing on the scene's ground plane, seen through a
// random similarity (the scene's up is not its z), random constraints.
World random_world(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  World w;
  w.georef.crs = "EPSG:32632";
  const double s = 0.5 + 1.5 * u(rng);  // metres per scene unit
  const Mat3 r = random_rotation(rng);
  w.georef.scene_to_crs.topLeftCorner<3, 3>() = s * r;
  w.georef.scene_to_crs.topRightCorner<3, 1>() = Vec3(500000 + 1000 * u(rng), 5000000, 200);
  // Build in a local ENU (metres), then map into the scene.
  auto to_scene = [&](const Vec3& enu) { return Vec3(r.transpose() * (enu - Vec3(0, 0, 0)) / s); };
  std::vector<std::pair<Vec3, Vec3>> boxes;
  const int n = 1 + int(u(rng) * 3);
  for (int i = 0; i < n; ++i) {
    const Vec3 c(-15 + 30 * u(rng), -15 + 30 * u(rng), 0);
    const Vec3 half(3 + 5 * u(rng), 3 + 5 * u(rng), 0);
    boxes.push_back({c - half, c + half + Vec3(0, 0, 8 + 20 * u(rng))});
  }
  // Mesh vertices in scene coordinates: map the corners (a box stays a box).
  for (const auto& [lo, hi] : boxes) {
    TriangleMesh b;
    add_box(&b, lo, hi);
    const int base = int(w.mesh.vertices.size());
    for (const Vec3& v : b.vertices) w.mesh.vertices.push_back(to_scene(v));
    for (const Face& f : b.faces) w.mesh.faces.push_back({base + f[0], base + f[1], base + f[2]});
  }
  w.takeoff = to_scene(Vec3(45, 0, 0));
  MissionOptions& o = w.options;
  o.min_altitude = 5 * u(rng);
  o.max_altitude = 25 + 50 * u(rng);
  o.min_mesh_distance = 1 + 3 * u(rng);
  o.gimbal_pitch_min = -90;
  o.gimbal_pitch_max = -20 + 40 * u(rng);
  o.target_gsd = u(rng) < 0.5 ? 0 : 2 + 3 * u(rng);
  o.max_waypoints = 2 + int(8 * u(rng));
  o.speed = 3 + 7 * u(rng);
  o.time_per_photo = 1 + 4 * u(rng);
  o.battery_minutes = 1.5 + 5 * u(rng);
  o.infeasible = u(rng) < 0.8 ? "move" : "drop";
  // A keep-out box (scene) and a keep-out triangle (lon/lat, through the frame).
  if (u(rng) < 0.7) {
    const Vec3 c = to_scene(Vec3(-30 + 60 * u(rng), -30 + 60 * u(rng), 10 + 20 * u(rng)));
    const Vec3 h = Vec3::Constant(4 / s);
    w.keep_outs.boxes.push_back({"box", c - h, c + h});
  }
  if (u(rng) < 0.7) {
    const GeoFrame frame(w.georef);
    KeepOutPolygon p;
    p.name = "triangle";
    const Vec2 c(-30 + 60 * u(rng), -30 + 60 * u(rng));
    for (int k = 0; k < 3; ++k) {
      const double a = 2 * M_PI * k / 3;
      const Vec3 enu(c.x() + 8 * std::cos(a), c.y() + 8 * std::sin(a), 0);
      const Geodetic g = frame.to_wgs84(to_scene(enu));
      p.lonlat.emplace_back(g.longitude, g.latitude);
    }
    p.floor = 5 * u(rng);
    p.ceiling = p.floor + 10 + 30 * u(rng);
    w.keep_outs.polygons.push_back(p);
  }
  // Suggestions all around, looking at the boxes' centres.
  const int count = 3 + int(u(rng) * 12);
  for (int i = 0; i < count; ++i) {
    const auto& [lo, hi] = boxes[std::size_t(i) % boxes.size()];
    const Vec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const double a = 2 * M_PI * u(rng);
    const Vec3 eye = centre + Vec3(25 * std::cos(a), 25 * std::sin(a), -10 + 40 * u(rng));
    // The look-at point: where the ray from the centre to the eye leaves the box.
    const Vec3 d = eye - centre;
    double t = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
      if (d[k] != 0) t = std::min(t, half[k] / std::abs(d[k]));
    const Vec3 target = centre + t * d;
    MissionInput m;
    m.label = "nbv_" + std::to_string(i + 1);
    m.rank = i + 1;
    m.look_at = to_scene(target);
    m.camera = PinholeCamera::look_at(to_scene(eye), m.look_at, r.transpose() * Vec3(0, 0, 1), 1000,
                                      1000, 639.5, 479.5, 1280, 960);
    m.energy = double(i);
    w.suggestions.push_back(m);
  }
  return w;
}

// Independent check of one point of the path.
std::string violation(const World& w, const GeoFrame& f, const RayCaster& caster, const Vec3& p,
                      bool takeoff_leg) {
  const MissionOptions& o = w.options;
  const double h = f.crs_height(p) - f.crs_height(w.takeoff);
  if ((!takeoff_leg && h < o.min_altitude - 1e-6) || h > o.max_altitude + 1e-6) return "altitude";
  if (!takeoff_leg && caster.closest_point(p) * f.metres_per_unit() < o.min_mesh_distance * (1 - 1e-9))
    return "mesh distance";
  for (const KeepOutBox& b : w.keep_outs.boxes)
    if ((p.array() >= b.min.array()).all() && (p.array() <= b.max.array()).all()) return "keep-out box";
  for (const KeepOutPolygon& poly : w.keep_outs.polygons) {
    std::vector<Vec2> ring;
    for (const Vec2& ll : poly.lonlat) ring.push_back(f.crs_from_wgs84({ll.y(), ll.x(), 0}).head<2>());
    if (h >= poly.floor && h <= poly.ceiling && in_ring(ring, f.to_crs(p).head<2>())) return "keep-out polygon";
  }
  return {};
}

std::string leg_violation(const World& w, const GeoFrame& f, const RayCaster& caster, const Vec3& a,
                          const Vec3& b, bool takeoff_leg) {
  const double step = 0.2 * w.options.min_mesh_distance / f.metres_per_unit();
  const int n = std::max(50, int((b - a).norm() / step) + 1);
  for (int i = 0; i <= n; ++i) {
    const std::string v = violation(w, f, caster, a + (b - a) * (double(i) / n), takeoff_leg);
    if (!v.empty()) return v;
  }
  return {};
}

TEST(MissionPlan, RandomScenesNoWaypointOrLegViolatesAConstraint) {
  std::mt19937 rng(2026);
  int planned = 0, refused = 0, moved = 0, dropped = 0, flights_total = 0;
  for (int trial = 0; trial < 40; ++trial) {
    World w = random_world(rng);
    const GeoFrame f(w.georef);
    const RayCaster caster(w.mesh);
    const Airspace air(caster, f, w.takeoff, w.options, w.keep_outs);
    MissionPlan plan;
    try {
      plan = plan_mission(w.suggestions, air);
    } catch (const Error& e) {
      ++refused;  // nothing feasible: allowed, with a one-line reason
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      continue;
    }
    ++planned;
    const MissionOptions& o = w.options;
    const Vec3 up_top = plan.climb_top - plan.takeoff;
    EXPECT_LT((up_top.normalized() - f.up()).norm(), 1e-9) << "the climb is vertical";
    EXPECT_EQ(leg_violation(w, f, caster, plan.takeoff, plan.climb_top, true), "") << "trial " << trial;
    for (const Waypoint& wp : plan.waypoints) {
      EXPECT_EQ(violation(w, f, caster, wp.position, false), "") << "trial " << trial << " " << wp.label;
      const double pitch = f.pitch(wp.look_at - wp.position);
      EXPECT_GE(pitch, o.gimbal_pitch_min - 1e-6);
      EXPECT_LE(pitch, o.gimbal_pitch_max + 1e-6);
      if (o.target_gsd > 0) {
        EXPECT_LE(100 * (wp.look_at - wp.position).norm() * f.metres_per_unit() / 1000.0, o.target_gsd * (1 + 1e-6));
      }
      moved += wp.moved;
    }
    for (const Note& n : plan.notes) dropped += n.action == "dropped";
    std::size_t photos = 0;
    for (const Flight& fl : plan.flights) {
      ++flights_total;
      ASSERT_GE(fl.points.size(), 3u);
      EXPECT_EQ(fl.points.front().position, plan.climb_top);
      EXPECT_EQ(fl.points.back().position, plan.climb_top);
      EXPECT_LE(int(fl.waypoints.size()), o.max_waypoints);
      double length = 0;
      for (std::size_t i = 0; i + 1 < fl.points.size(); ++i) {
        const Vec3& a = fl.points[i].position;
        const Vec3& b = fl.points[i + 1].position;
        EXPECT_EQ(leg_violation(w, f, caster, a, b, false), "") << "trial " << trial << " leg " << i;
        length += (b - a).norm() * f.metres_per_unit();
      }
      length += 2 * plan.climb_height;
      const double minutes = (length / o.speed + double(fl.waypoints.size()) * o.time_per_photo) / 60;
      EXPECT_NEAR(minutes, fl.minutes, 1e-9);
      EXPECT_LE(minutes, o.battery_minutes + 1e-9) << "trial " << trial;
      photos += fl.waypoints.size();
    }
    EXPECT_EQ(photos, plan.waypoints.size());
    EXPECT_EQ(plan.waypoints.size() + std::size_t(std::count_if(plan.notes.begin(), plan.notes.end(),
                                                                [](const Note& n) { return n.action == "dropped"; })),
              w.suggestions.size());
  }
  // The random worlds exercise every branch.
  EXPECT_GE(planned, 25);
  EXPECT_GT(moved, 0);
  EXPECT_GT(dropped, 0);
  EXPECT_GT(flights_total, planned);
  std::cout << planned << " planned, " << refused << " refused, " << moved << " moved, " << dropped
            << " dropped, " << flights_total << " flights\n";
}

TEST(MissionRoute, TwoOptNeverLongerThanNearestNeighbour) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-100, 100);
  int shorter = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Vec3> p(1 + std::size_t(trial % 40));
    for (Vec3& v : p) v = Vec3(u(rng), u(rng), u(rng) * 0.2);
    const Vec3 start(u(rng), u(rng), 0);
    const std::vector<int> nn = nearest_neighbour_order(start, p);
    const std::vector<int> best = route_order(start, p);
    std::vector<int> sorted = best;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], int(i)) << "a permutation";
    const double a = tour_length(start, p, nn), b = tour_length(start, p, best);
    EXPECT_LE(b, a + 1e-9);
    shorter += b < a - 1e-9;
  }
  EXPECT_GT(shorter, 50) << "2-opt improves on nearest neighbour on most random sets";
}

TEST(MissionRoute, SquareIsToured) {
  // Four corners of a square from a start at one corner: the perimeter.
  const std::vector<Vec3> p = {Vec3(10, 10, 0), Vec3(0, 10, 0), Vec3(10, 0, 0)};
  EXPECT_NEAR(tour_length(Vec3::Zero(), p, route_order(Vec3::Zero(), p)), 40.0, 1e-12);
}

TEST(MissionKeepOut, SelfIntersectingPolygonIsAnError) {
  const std::string bowtie = R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {"name": "bowtie", "floor": 0, "ceiling": 50},
      "geometry": {"type": "Polygon", "coordinates": [[[9.0, 45.0], [9.001, 45.001], [9.001, 45.0], [9.0, 45.001], [9.0, 45.0]]]}}]})";
  try {
    parse_keep_out_geojson(bowtie, "k.geojson");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("intersects itself"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("k.geojson"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(ring_self_intersects({Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(1, 1)}));  // folds back
  EXPECT_FALSE(ring_self_intersects({Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(1, 1), Vec2(0, 2)}));
  const KeepOuts ok = parse_keep_out_geojson(R"({"type": "Feature", "properties": {"ceiling": 30},
      "geometry": {"type": "Polygon", "coordinates": [[[9.0, 45.0], [9.001, 45.0], [9.001, 45.001], [9.0, 45.0]]]}})", "k");
  ASSERT_EQ(ok.polygons.size(), 1u);
  EXPECT_EQ(ok.polygons[0].lonlat.size(), 3u);
  EXPECT_EQ(ok.polygons[0].ceiling, 30);
  EXPECT_TRUE(std::isinf(ok.polygons[0].floor));
  for (const char* bad : {
           R"({"type": "Feature", "geometry": {"type": "Point", "coordinates": [9, 45]}})",
           R"({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[9, 45], [9.1, 45], [9, 45]]]}})",
           R"({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[9, 45], [9.1, 45], [9, 45.1], [9, 45]], [[9, 45], [9.01, 45], [9, 45.01], [9, 45]]]}})",
           R"({"type": "Feature", "properties": {"floor": 10, "ceiling": 5}, "geometry": {"type": "Polygon", "coordinates": [[[9, 45], [9.1, 45], [9, 45.1], [9, 45]]]}})",
           R"({"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[9, 95], [9.1, 45], [9, 45.1], [9, 95]]]}})",
           R"([1, 2])"})
    EXPECT_THROW(parse_keep_out_geojson(bad, "k"), Error) << bad;
  EXPECT_THROW(parse_keep_out_box("1,2,3"), Error);
  EXPECT_THROW(parse_keep_out_box("1,2,3,0,5,6"), Error);
  EXPECT_EQ(parse_keep_out_box("0,0,0,1,2,3").max, Vec3(1, 2, 3));
}

TEST(MissionPlan, ConstraintsThatLeaveNoFeasiblePoseAreAnError) {
  std::mt19937 rng(3);
  World w = random_world(rng);
  // Views from at most 3 m up, looking at least 80 degrees down: none sees
  // the boxes' sides (4 m and higher) or tops.
  w.options.max_altitude = 3;
  w.options.min_altitude = 0;
  w.options.min_mesh_distance = 1;
  w.options.gimbal_pitch_max = -80;
  w.options.infeasible = "move";
  w.keep_outs = {};
  const GeoFrame f(w.georef);
  const RayCaster caster(w.mesh);
  const Airspace air(caster, f, w.takeoff, w.options, w.keep_outs);
  try {
    plan_mission(w.suggestions, air);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no suggestion can be flown"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace meshnbv::test
