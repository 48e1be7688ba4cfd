// mission.svg: the flights seen from above over the mesh (writers.h).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "flight_points.h"
#include "meshnbv/mission/writers.h"

namespace meshnbv::mission {
namespace {

// Convex hull (monotone chain), counter-clockwise.
std::vector<Vec2> hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

const char* const kColours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"};

}  // namespace

std::string mission_svg(const MissionPlan& plan, const GeoFrame& frame, const TriangleMesh& mesh,
                        const KeepOuts& keep_outs) {
  // Everything in CRS east/north, relative to the take-off point.
  const Vec2 origin = frame.to_crs(plan.takeoff).head<2>();
  auto en = [&](const Vec3& scene) { return Vec2(frame.to_crs(scene).head<2>() - origin); };
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
  auto grow = [&](const Vec2& p) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); };
  for (const Vec3& v : mesh.vertices) grow(en(v));
  for (const Flight& f : plan.flights)
    for (const PathPoint& p : f.points) grow(en(p.position));
  const double margin = 0.05 * std::max(1.0, (hi - lo).maxCoeff());
  lo -= Vec2::Constant(margin);
  hi += Vec2::Constant(margin);
  const double scale = 800.0 / std::max(1e-9, (hi - lo).maxCoeff());
  auto xy = [&](const Vec2& p) {
    return fixed((p.x() - lo.x()) * scale, 1) + "," + fixed((hi.y() - p.y()) * scale, 1);  // north up
  };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fixed((hi.x() - lo.x()) * scale, 0)
    << "\" height=\"" << fixed((hi.y() - lo.y()) * scale + 20 * double(plan.flights.size() + 1), 0)
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // The mesh: faces that face up (roofs, ground), from above.
  s << "<g fill=\"#bbbbbb\" stroke=\"none\">\n";
  for (const Face& f : mesh.faces) {
    const Vec3 &a = mesh.vertices[std::size_t(f[0])], &b = mesh.vertices[std::size_t(f[1])],
               &c = mesh.vertices[std::size_t(f[2])];
    if ((b - a).cross(c - a).dot(frame.up()) <= 0) continue;
    s << "<polygon points=\"" << xy(en(a)) << " " << xy(en(b)) << " " << xy(en(c)) << "\"/>\n";
  }
  s << "</g>\n<g fill=\"#ff000033\" stroke=\"#aa0000\">\n";
  for (const KeepOutBox& b : keep_outs.boxes) {
    std::vector<Vec2> corners;
    for (int i = 0; i < 8; ++i)
      corners.push_back(en(Vec3(i & 1 ? b.max.x() : b.min.x(), i & 2 ? b.max.y() : b.min.y(),
                                i & 4 ? b.max.z() : b.min.z())));
    s << "<polygon points=\"";
    for (const Vec2& p : hull(corners)) s << xy(p) << " ";
    s << "\"><title>" << b.name << "</title></polygon>\n";
  }
  const double h = frame.to_wgs84(plan.takeoff).height;
  for (const KeepOutPolygon& p : keep_outs.polygons) {
    s << "<polygon points=\"";
    for (const Vec2& ll : p.lonlat) s << xy(Vec2(frame.crs_from_wgs84({ll.y(), ll.x(), h}).head<2>() - origin)) << " ";
    s << "\"><title>" << p.name << "</title></polygon>\n";
  }
  s << "</g>\n";
  for (std::size_t k = 0; k < plan.flights.size(); ++k) {
    const char* colour = kColours[k % 6];
    s << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\" points=\"" << xy(Vec2::Zero());
    for (const PathPoint& p : plan.flights[k].points) s << " " << xy(en(p.position));
    s << " " << xy(Vec2::Zero()) << "\"/>\n";
    for (const PathPoint& p : plan.flights[k].points)
      if (p.waypoint >= 0)
        s << "<circle r=\"4\" fill=\"" << colour << "\" cx=\"" << fixed((en(p.position).x() - lo.x()) * scale, 1)
          << "\" cy=\"" << fixed((hi.y() - en(p.position).y()) * scale, 1) << "\"><title>"
          << plan.waypoints[std::size_t(p.waypoint)].label << "</title></circle>\n";
    s << "<text x=\"10\" y=\"" << fixed((hi.y() - lo.y()) * scale + 18 * double(k + 1), 0) << "\" fill=\""
      << colour << "\">flight " << k + 1 << ": " << plan.flights[k].waypoints.size() << " photos, "
      << fixed(plan.flights[k].minutes, 1) << " min</text>\n";
  }
  const Vec2 t = Vec2::Zero();
  s << "<rect x=\"" << fixed((t.x() - lo.x()) * scale - 5, 1) << "\" y=\"" << fixed((hi.y() - t.y()) * scale - 5, 1)
    << "\" width=\"10\" height=\"10\" fill=\"black\"><title>take-off</title></rect>\n</svg>\n";
  return s.str();
}

}  // namespace meshnbv::mission
