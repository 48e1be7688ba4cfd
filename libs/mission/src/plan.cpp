// Placing the suggestions within the constraints, and the flights (plan.h).
#include "meshnbv/mission/plan.h"

#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "meshnbv/error.h"

namespace meshnbv::mission {
namespace {

constexpr double kGoldenAngle = 2.39996322972865332;
constexpr double kClearanceMargin = 1.1;  // waypoints keep 10% more than the limit, for their legs

// Why a camera at `p` looking at `look_at` breaks a per-photo constraint
// (pitch, GSD, and everything the airspace checks), or empty.
std::string pose_problem(const Airspace& air, const Vec3& p, const Vec3& look_at, double fx) {
  const MissionOptions& o = air.options();
  const GeoFrame& f = air.frame();
  std::ostringstream why;
  const double pitch = f.pitch(look_at - p);
  if (pitch < o.gimbal_pitch_min - 1e-9 || pitch > o.gimbal_pitch_max + 1e-9) {
    why << "gimbal pitch " << pitch << " degrees is outside [" << o.gimbal_pitch_min << ", "
        << o.gimbal_pitch_max << "]";
    return why.str();
  }
  if (o.target_gsd > 0) {
    const double gsd_cm = 100.0 * (look_at - p).norm() * f.metres_per_unit() / fx;
    if (gsd_cm > o.target_gsd * (1 + 1e-9)) {
      why << "ground sampling distance " << gsd_cm << " cm/pixel exceeds target_gsd " << o.target_gsd;
      return why.str();
    }
  }
  return air.point_problem(p);
}

// A pose that is fine and leaves room for its legs.
bool feasible(const Airspace& air, const RayCaster& caster, const Vec3& p, const Vec3& look_at,
              double fx) {
  if (!pose_problem(air, p, look_at, fx).empty()) return false;
  if (caster.closest_point(p) < kClearanceMargin * air.mesh_clearance()) return false;
  // The look-at point must stay in sight.
  return caster.segment_clear(p, look_at, 1e-3, 0.0);
}

// The nearest feasible position: spheres of growing radius around `c`.
std::optional<Vec3> nearest_feasible(const Airspace& air, const RayCaster& caster, const Vec3& c,
                                     const Vec3& look_at, double fx) {
  const double dist = (look_at - c).norm();
  const double step = std::max(0.5 * air.mesh_clearance(), 0.02 * dist);
  const int directions = 128;
  for (int k = 1; k <= 100; ++k) {
    const double r = step * k;
    std::optional<Vec3> best;
    double best_d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < directions; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / directions;
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
      const Vec3 d(rho * std::cos(kGoldenAngle * i), rho * std::sin(kGoldenAngle * i), z);
      const Vec3 p = c + r * d;
      if (feasible(air, caster, p, look_at, fx) && (p - c).norm() < best_d) {
        best = p;
        best_d = (p - c).norm();
      }
    }
    if (best) return best;
  }
  return std::nullopt;
}

PinholeCamera level_camera(const PinholeCamera& k, const Vec3& eye, const Vec3& target, const Vec3& up) {
  // A drone's gimbal has no roll: the image's up is the world's (a straight
  // down view keeps its heading through the same call with another up).
  const Vec3 dir = (target - eye).normalized();
  const Vec3 use_up = std::abs(dir.dot(up)) > 0.999 ? Vec3(-k.down()) : up;
  return PinholeCamera::look_at(eye, target, use_up, k.fx, k.fy, k.cx, k.cy, k.width, k.height);
}

}  // namespace

double MissionPlan::total_minutes() const {
  double m = 0;
  for (const Flight& f : flights) m += f.minutes;
  return m;
}

namespace {

// Each suggestion kept as it is, moved, or dropped (with a note).
std::vector<Waypoint> place_suggestions(const std::vector<MissionInput>& in, const Airspace& air,
                                        const RayCaster& caster, const Rescore& rescore,
                                        std::vector<Note>* notes) {
  std::vector<Waypoint> out;
  const GeoFrame& f = air.frame();
  for (const MissionInput& s : in) {
    Waypoint w;
    w.label = s.label;
    w.rank = s.rank;
    w.look_at = s.look_at;
    w.position = s.camera.center();
    w.energy = w.original_energy = s.energy;
    const std::string problem = pose_problem(air, w.position, s.look_at, s.camera.fx);
    const bool margin_ok = caster.closest_point(w.position) >= kClearanceMargin * air.mesh_clearance();
    if (!problem.empty() || !margin_ok) {
      const std::string why = problem.empty() ? "too close to the mesh for its legs" : problem;
      if (air.options().infeasible == "drop") {
        notes->push_back({s.label, "dropped", why});
        continue;
      }
      const std::optional<Vec3> p = nearest_feasible(air, caster, w.position, s.look_at, s.camera.fx);
      if (!p) {
        notes->push_back({s.label, "dropped", why + "; no feasible pose nearby"});
        continue;
      }
      w.moved = true;
      w.moved_by = (*p - w.position).norm() * f.metres_per_unit();
      w.position = *p;
      if (rescore) w.energy = rescore(level_camera(s.camera, *p, s.look_at, f.up()), s.region);
      std::ostringstream note;
      note << why << "; moved " << w.moved_by << " m";
      if (rescore) note << ", energy " << w.original_energy << " -> " << w.energy;
      notes->push_back({s.label, "moved", note.str()});
    }
    w.height = air.height(w.position);
    w.geo = f.to_wgs84(w.position);
    w.heading = f.heading(w.position, w.look_at - w.position);
    w.pitch = f.pitch(w.look_at - w.position);
    out.push_back(w);
  }
  return out;
}

// The lowest climb height above the take-off point that is a safe path point.
double climb_height(const Airspace& air, const RayCaster& caster) {
  const MissionOptions& o = air.options();
  const Vec3& up = air.frame().up();
  const double mpu = air.frame().metres_per_unit();
  const double step = std::max(0.5, 0.25 * o.min_mesh_distance);
  for (double h = std::max(o.min_altitude, kClearanceMargin * o.min_mesh_distance) + 0.01;
       h <= o.max_altitude; h += step) {
    const Vec3 top = air.takeoff() + up * (h / mpu);
    if (air.point_problem(top).empty() &&
        caster.closest_point(top) >= kClearanceMargin * air.mesh_clearance() &&
        air.leg_problem(air.takeoff(), top, true).empty())
      return h;
  }
  throw Error("no safe climb above the take-off point within max_altitude " +
              format_option_value(o.max_altitude) + " m (mesh, keep-out volumes or altitude limits "
              "block it): choose another --takeoff");
}

}  // namespace
}  // namespace meshnbv::mission

namespace meshnbv::mission {
namespace {

// A leg from a to b: straight, or over the obstacle (climb, cross, descend).
struct Leg {
  std::vector<Vec3> via;  // detour corners between a and b
  double length = 0;      // scene units
  std::string problem;    // non-empty: no way found
};

// Over the obstacle: climb at a, cross, descend at b (the lowest that works).
std::optional<Leg> climb_detour(const Airspace& air, const Vec3& a, const Vec3& b) {
  const Vec3& up = air.frame().up();
  const double step = std::max(2.0, 2.0 * air.options().min_mesh_distance) / air.frame().metres_per_unit();
  for (int k = 1; k <= 200; ++k) {
    const Vec3 a2 = a + up * (step * k), b2 = b + up * (step * k);
    if (air.height(a2) > air.options().max_altitude || air.height(b2) > air.options().max_altitude)
      break;
    if (air.point_problem(a2).empty() && air.point_problem(b2).empty() &&
        air.leg_problem(a, a2).empty() && air.leg_problem(a2, b2).empty() &&
        air.leg_problem(b2, b).empty())
      return Leg{{a2, b2}, (a2 - a).norm() + (b2 - a2).norm() + (b - b2).norm(), {}};
  }
  return std::nullopt;
}

// Around the obstacle: one corner beside the leg's midpoint, at the leg's
// height, on the side that needs the smaller offset.
std::optional<Leg> side_detour(const Airspace& air, const Vec3& a, const Vec3& b) {
  const Vec3& up = air.frame().up();
  Vec3 side = up.cross(b - a);
  if (side.norm() < 1e-12 * (b - a).norm() || (b - a).norm() == 0) return std::nullopt;
  side.normalize();
  const double step = std::max(2.0, 2.0 * air.options().min_mesh_distance) / air.frame().metres_per_unit();
  const Vec3 mid = 0.5 * (a + b);
  for (int k = 1; k <= 100; ++k)
    for (double sign : {1.0, -1.0}) {
      const Vec3 m = mid + sign * side * (step * k);
      if (air.point_problem(m).empty() && air.leg_problem(a, m).empty() && air.leg_problem(m, b).empty())
        return Leg{{m}, (m - a).norm() + (b - m).norm(), {}};
    }
  return std::nullopt;
}

Leg plan_leg(const Airspace& air, const Vec3& a, const Vec3& b) {
  Leg leg;
  leg.problem = air.leg_problem(a, b);
  if (leg.problem.empty()) {
    leg.length = (b - a).norm();
    return leg;
  }
  const std::optional<Leg> over = climb_detour(air, a, b), around = side_detour(air, a, b);
  if (over && (!around || over->length <= around->length)) return *over;
  if (around) return *around;
  return leg;
}

// Greedy split of the tour into flights that fit the battery and the
// waypoint limit; waypoints no leg reaches are dropped with a note.
class FlightBuilder {
 public:
  FlightBuilder(const Airspace& air, const std::vector<Waypoint>& wps, const Vec3& top, double climb_m,
                std::vector<Note>* notes)
      : air_(air), wps_(wps), top_(top), climb_m_(climb_m), notes_(notes) {}

  void add(int w) {
    const Vec3& p = wps_[std::size_t(w)].position;
    Leg back = plan_leg(air_, p, top_);
    if (!back.problem.empty()) return drop(w, "no way back to the take-off point: " + back.problem);
    Leg to = plan_leg(air_, last(), p);
    if (!to.problem.empty() && !cur_.waypoints.empty()) {
      close();
      to = plan_leg(air_, top_, p);
    }
    if (!to.problem.empty()) return drop(w, "no way from the take-off point: " + to.problem);
    if (!cur_.waypoints.empty() &&
        (int(cur_.waypoints.size()) + 1 > air_.options().max_waypoints ||
         minutes(len_ + to.length + back.length, cur_.waypoints.size() + 1) > air_.options().battery_minutes)) {
      close();
      to = plan_leg(air_, top_, p);
      if (!to.problem.empty()) return drop(w, "no way from the take-off point: " + to.problem);
    }
    const double alone = minutes(to.length + back.length, 1);
    if (cur_.waypoints.empty() && alone > air_.options().battery_minutes) {
      std::ostringstream why;
      why << "a flight to it alone takes " << alone << " min, more than battery_minutes "
          << air_.options().battery_minutes;
      return drop(w, why.str());
    }
    append(to, w);
    back_ = back;
  }

  std::vector<Flight> finish() {
    close();
    return std::move(flights_);
  }

 private:
  const Vec3& last() const {
    return cur_.points.size() > 1 ? cur_.points.back().position : top_;
  }
  double minutes(double length_units, std::size_t photos) const {
    const MissionOptions& o = air_.options();
    const double metres = length_units * air_.frame().metres_per_unit() + 2 * climb_m_;
    return (metres / o.speed + double(photos) * o.time_per_photo) / 60.0;
  }
  void drop(int w, const std::string& why) { notes_->push_back({wps_[std::size_t(w)].label, "dropped", why}); }
  void detour_note(int w, const Leg& leg) {
    if (leg.via.empty()) return;
    ++cur_.detours;
    notes_->push_back({wps_[std::size_t(w)].label, "detour",
                       leg.via.size() == 2 ? "leg climbs over an obstacle" : "leg goes around an obstacle"});
  }
  void append(const Leg& to, int w) {
    if (cur_.points.empty()) cur_.points.push_back({top_, -1});
    for (const Vec3& v : to.via) cur_.points.push_back({v, -1});
    cur_.points.push_back({wps_[std::size_t(w)].position, w});
    cur_.waypoints.push_back(w);
    len_ += to.length;
    detour_note(w, to);
  }
  void close() {
    if (cur_.waypoints.empty()) return;
    for (const Vec3& v : back_.via) cur_.points.push_back({v, -1});
    if (!back_.via.empty()) ++cur_.detours;
    cur_.points.push_back({top_, -1});
    len_ += back_.length;
    cur_.length_m = len_ * air_.frame().metres_per_unit() + 2 * climb_m_;
    cur_.minutes = minutes(len_, cur_.waypoints.size());
    flights_.push_back(std::move(cur_));
    cur_ = Flight();
    len_ = 0;
  }

  const Airspace& air_;
  const std::vector<Waypoint>& wps_;
  Vec3 top_;
  double climb_m_;
  std::vector<Note>* notes_;
  std::vector<Flight> flights_;
  Flight cur_;
  double len_ = 0;
  Leg back_;
};

}  // namespace

MissionPlan plan_mission(const std::vector<MissionInput>& suggestions, const Airspace& air,
                         const Rescore& rescore) {
  const RayCaster& caster = air.caster();
  MissionPlan plan;
  plan.takeoff = air.takeoff();
  plan.takeoff_geo = air.frame().to_wgs84(plan.takeoff);
  plan.climb_height = climb_height(air, caster);
  plan.climb_top = plan.takeoff + air.frame().up() * (plan.climb_height / air.frame().metres_per_unit());
  std::vector<Waypoint> placed = place_suggestions(suggestions, air, caster, rescore, &plan.notes);
  std::vector<Vec3> points;
  for (const Waypoint& w : placed) points.push_back(w.position);
  const std::vector<int> order = route_order(plan.climb_top, points);
  FlightBuilder builder(air, placed, plan.climb_top, plan.climb_height, &plan.notes);
  for (int w : order) builder.add(w);
  std::vector<Flight> flights = builder.finish();
  // Keep the flown waypoints only, renumbered in flight order.
  for (std::size_t k = 0; k < flights.size(); ++k) {
    Flight& f = flights[k];
    std::map<int, int> renumber;
    for (std::size_t i = 0; i < f.waypoints.size(); ++i) {
      Waypoint w = placed[std::size_t(f.waypoints[i])];
      w.flight = int(k);
      w.order = int(i);
      renumber[f.waypoints[i]] = int(plan.waypoints.size());
      plan.waypoints.push_back(w);
    }
    for (int& w : f.waypoints) w = renumber[w];
    for (PathPoint& p : f.points)
      if (p.waypoint >= 0) p.waypoint = renumber[p.waypoint];
  }
  plan.flights = std::move(flights);
  if (plan.waypoints.empty()) {
    std::string why = "no suggestion can be flown within the constraints";
    if (!plan.notes.empty()) why += " (" + plan.notes.front().label + ": " + plan.notes.front().reason + ")";
    throw Error(why);
  }
  return plan;
}

}  // namespace meshnbv::mission
