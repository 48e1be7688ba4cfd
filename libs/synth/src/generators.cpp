#include "meshnbv/synth/generators.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "meshnbv/error.h"

namespace meshnbv::synth {
namespace {

int cells(double extent, double edge) { return std::max(1, int(std::ceil(extent / edge - 1e-9))); }

// Merges vertices at bitwise-equal positions (the generators compute shared
// vertices with the same formula) so that components come out closed.
void weld_exact(TriangleMesh* m) {
  std::map<std::tuple<double, double, double>, int> index;
  std::vector<int> remap(m->vertices.size());
  std::vector<Vec3> welded;
  for (std::size_t i = 0; i < m->vertices.size(); ++i) {
    const Vec3& p = m->vertices[i];
    auto [it, inserted] = index.try_emplace({p.x(), p.y(), p.z()}, int(welded.size()));
    if (inserted) welded.push_back(p);
    remap[i] = it->second;
  }
  m->vertices = std::move(welded);
  for (auto& f : m->faces)
    for (int& i : f) i = remap[i];
}

void set_material(TriangleMesh* m, int material) {
  m->face_attributes[kMaterialAttribute] = std::vector<float>(m->faces.size(), float(material));
}

// Adds a grid quad patch: origin + i/nu * du + j/nv * dv, wound so the normal
// is du x dv (flip = true reverses it).
void add_patch(TriangleMesh* m, const Vec3& origin, const Vec3& du, const Vec3& dv, int nu, int nv,
               bool flip) {
  const int base = int(m->vertices.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      m->vertices.push_back(origin + du * (double(i) / nu) + dv * (double(j) / nv));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      if (!flip) {
        m->faces.push_back({a, b, d});
        m->faces.push_back({a, d, c});
      } else {
        m->faces.push_back({a, d, b});
        m->faces.push_back({a, c, d});
      }
    }
}

}  // namespace

TriangleMesh make_box(const Vec3& min, const Vec3& max, double edge, int material) {
  if (!(edge > 0) || !((max - min).minCoeff() > 0)) throw Error("make_box: empty box or edge length <= 0");
  TriangleMesh m;
  const Vec3 e = max - min;
  const int n[3] = {cells(e.x(), edge), cells(e.y(), edge), cells(e.z(), edge)};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Vec3 du = Vec3::Zero(), dv = Vec3::Zero();
    du[u] = e[u];
    dv[v] = e[v];
    for (int side = 0; side < 2; ++side) {
      Vec3 origin = min;
      if (side) origin[axis] = max[axis];
      // du x dv points along +axis; the min side must point along -axis.
      add_patch(&m, origin, du, dv, n[u], n[v], side == 0);
    }
  }
  weld_exact(&m);
  set_material(&m, material);
  return m;
}

TriangleMesh make_ground(const Vec3& min, const Vec3& max, double edge, int material) {
  TriangleMesh m;
  const Vec3 e = max - min;
  add_patch(&m, min, Vec3(e.x(), 0, 0), Vec3(0, e.y(), 0), cells(e.x(), edge), cells(e.y(), edge),
            false);
  set_material(&m, material);
  return m;
}

TriangleMesh make_prism(const Vec3& base, double radius, double height, int sides, double edge,
                        int material) {
  if (sides < 3 || !(radius > 0) || !(height > 0) || !(edge > 0))
    throw Error("make_prism: need >= 3 sides and positive radius, height and edge length");
  TriangleMesh m;
  const double side_len = 2 * radius * std::sin(M_PI / sides);
  const int ns = cells(side_len, edge), nv = cells(height, edge), nr = cells(radius, edge);
  const int rim = sides * ns;
  // Rim point k of the polygon scaled by s, at height z (same formula for
  // walls and caps, so the weld closes the prism).
  auto rim_point = [&](int k, double s, double z) {
    const int side = (k / ns) % sides, step = k % ns;
    const double a0 = 2 * M_PI * side / sides, a1 = 2 * M_PI * (side + 1) / sides;
    const Vec3 p0(std::cos(a0), std::sin(a0), 0), p1(std::cos(a1), std::sin(a1), 0);
    const Vec3 p = p0 + (p1 - p0) * (double(step) / ns);
    return Vec3(base.x() + radius * s * p.x(), base.y() + radius * s * p.y(), z);
  };
  // Walls: counter-clockwise rim seen from above, outward normals.
  for (int j = 0; j <= nv; ++j)
    for (int k = 0; k < rim; ++k) m.vertices.push_back(rim_point(k, 1.0, base.z() + height * j / nv));
  for (int j = 0; j < nv; ++j)
    for (int k = 0; k < rim; ++k) {
      const int a = j * rim + k, b = j * rim + (k + 1) % rim, c = a + rim, d = b + rim;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  // Caps: concentric rings down to a centre vertex.
  for (int cap = 0; cap < 2; ++cap) {
    const double z = base.z() + (cap ? height : 0.0);
    const int first = int(m.vertices.size());
    for (int r = nr; r >= 1; --r)
      for (int k = 0; k < rim; ++k) m.vertices.push_back(rim_point(k, double(r) / nr, z));
    const int centre = int(m.vertices.size());
    m.vertices.push_back(Vec3(base.x(), base.y(), z));
    auto add = [&](int a, int b, int c) {
      if (cap)
        m.faces.push_back({a, b, c});
      else
        m.faces.push_back({a, c, b});
    };
    for (int r = 0; r + 1 < nr; ++r)
      for (int k = 0; k < rim; ++k) {
        const int a = first + r * rim + k, b = first + r * rim + (k + 1) % rim;
        const int c = a + rim, d = b + rim;  // inner ring
        add(a, b, d);
        add(a, d, c);
      }
    const int inner = first + (nr - 1) * rim;
    for (int k = 0; k < rim; ++k) add(inner + k, inner + (k + 1) % rim, centre);
  }
  weld_exact(&m);
  set_material(&m, material);
  return m;
}

double default_edge_length(const std::string& scene) {
  if (scene == "building") return 0.3;
  if (scene == "fortress") return 0.6;
  if (scene == "city") return 0.8;
  return 0.0;
}

TriangleMesh make_building(const GeneratorOptions& o) {
  const double e = o.edge_length > 0 ? o.edge_length : default_edge_length("building");
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  const double W = 12.0 + 2.0 * jitter(rng), D = 8.0 + 1.5 * jitter(rng), H = 9.0 + 2.0 * jitter(rng);
  TriangleMesh m = make_box(Vec3(-W / 2, -D / 2, 0), Vec3(W / 2, D / 2, H), e, 2);
  // Flat roof of the block in plaster.
  auto& mat = m.face_attributes[kMaterialAttribute];
  for (std::size_t f = 0; f < m.num_faces(); ++f)
    if (m.face_normal(f).z() > 0.9) mat[f] = 0;
  // Parapet walls along the roof edge.
  const double t = 0.3, h = 0.9;
  m.append(make_box(Vec3(-W / 2, -D / 2, H), Vec3(W / 2, -D / 2 + t, H + h), e, 1));
  m.append(make_box(Vec3(-W / 2, D / 2 - t, H), Vec3(W / 2, D / 2, H + h), e, 1));
  m.append(make_box(Vec3(-W / 2, -D / 2 + t, H), Vec3(-W / 2 + t, D / 2 - t, H + h), e, 1));
  m.append(make_box(Vec3(W / 2 - t, -D / 2 + t, H), Vec3(W / 2, D / 2 - t, H + h), e, 1));
  // Roof details: a stair house, a chimney and a water tank.
  const double sx = W * (0.1 + 0.15 * jitter(rng)), sy = D * 0.1 * jitter(rng);
  m.append(make_box(Vec3(sx - 1.5, sy - 1.2, H), Vec3(sx + 1.5, sy + 1.2, H + 2.4), e, 0));
  m.append(make_box(Vec3(-W / 2 + 1.5, D / 2 - 1.6, H), Vec3(-W / 2 + 2.2, D / 2 - 0.9, H + 2.0), e, 1));
  m.append(make_prism(Vec3(W / 2 - 2.0, -D / 2 + 2.0, H), 0.8, 1.6, 12, e, 3));
  return m;
}

TriangleMesh make_fortress(const GeneratorOptions& o) {
  const double e = o.edge_length > 0 ? o.edge_length : default_edge_length("fortress");
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  const double S = 30.0 + 4.0 * jitter(rng);  // court side
  const double T = 2.0, Hw = 8.0 + jitter(rng), R = 3.5, Ht = 12.0 + 1.5 * jitter(rng);
  TriangleMesh m = make_ground(Vec3(-0.8 * S, -0.8 * S, 0), Vec3(0.8 * S, 0.8 * S, 0), 2.0 * e, 5);
  const double a = S / 2;
  m.append(make_box(Vec3(-a, -a - T / 2, 0), Vec3(a, -a + T / 2, Hw), e, 3));
  m.append(make_box(Vec3(-a, a - T / 2, 0), Vec3(a, a + T / 2, Hw), e, 3));
  m.append(make_box(Vec3(-a - T / 2, -a + T / 2, 0), Vec3(-a + T / 2, a - T / 2, Hw), e, 3));
  m.append(make_box(Vec3(a - T / 2, -a + T / 2, 0), Vec3(a + T / 2, a - T / 2, Hw), e, 3));
  for (int i = 0; i < 4; ++i) {
    const double x = (i & 1) ? a : -a, y = (i & 2) ? a : -a;
    m.append(make_prism(Vec3(x, y, 0), R, Ht, 12, e, 1));
  }
  // A keep in the court.
  m.append(make_box(Vec3(-4, -3, 0), Vec3(4, 3, 10.0 + 2.0 * jitter(rng)), e, 1));
  return m;
}

TriangleMesh make_city(const GeneratorOptions& o) {
  const double e = o.edge_length > 0 ? o.edge_length : default_edge_length("city");
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> height(6.0, 30.0), unit(0.0, 1.0);
  const int grid = 4;
  const double block = 10.0, street = 6.0, pitch = block + street;
  const double half = grid * pitch / 2.0;
  TriangleMesh m = make_ground(Vec3(-half, -half, 0), Vec3(half, half, 0), 2.0 * e, 5);
  const int facade[3] = {2, 1, 0};
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const double x0 = -half + street / 2 + i * pitch, y0 = -half + street / 2 + j * pitch;
      const double h = height(rng);
      const int material = facade[int(unit(rng) * 3) % 3];
      m.append(make_box(Vec3(x0, y0, 0), Vec3(x0 + block, y0 + block, h), e, material));
    }
  return m;
}

TriangleMesh make_scene_mesh(const std::string& name, const GeneratorOptions& options) {
  if (name == "building") return make_building(options);
  if (name == "fortress") return make_fortress(options);
  if (name == "city") return make_city(options);
  throw Error("unknown scene '" + name + "' (expected building, fortress, city or object)");
}

CameraLayout parse_camera_layout(const std::string& name) {
  if (name == "ring") return CameraLayout::Ring;
  if (name == "hemisphere") return CameraLayout::Hemisphere;
  if (name == "orbit") return CameraLayout::Orbit;
  if (name == "grid") return CameraLayout::Grid;
  throw Error("unknown camera layout '" + name + "' (expected ring, hemisphere, orbit or grid)");
}

std::string camera_layout_name(CameraLayout layout) {
  switch (layout) {
    case CameraLayout::Ring: return "ring";
    case CameraLayout::Hemisphere: return "hemisphere";
    case CameraLayout::Orbit: return "orbit";
    case CameraLayout::Grid: return "grid";
  }
  return "ring";
}

namespace {

// A survey flight's cameras (make_cameras' `grid`): nadir photos on a
// lawnmower grid whose outer rows and columns lie over the footprint's
// border, high enough that each photo reaches 1.25 grid steps from its
// centre on the floor (neighbours overlap by 60%, every point of the floor
// is in two photos at least along each axis).
std::vector<PinholeCamera> grid_cameras(const BoundingBox& box, const CameraSetOptions& o, double fx) {
  const Vec3 size = box.max - box.min;
  const double wx = std::max(size.x(), 1e-9 * box.diagonal()), wy = std::max(size.y(), 1e-9 * box.diagonal());
  const int cols = std::clamp(int(std::lround(std::sqrt(o.count * wx / wy))), 1, o.count);
  const int rows = (o.count + cols - 1) / cols;
  auto step = [](double w, int n) { return n > 1 ? w / (n - 1) : w; };
  auto at = [](double lo, double w, int i, int n) { return n > 1 ? lo + w * i / (n - 1) : lo + 0.5 * w; };
  // The widest step along x (a short last row spreads wider) and along y.
  const int last = o.count - (rows - 1) * cols;
  const double sx = step(wx, std::min(cols, last)), sy = step(wy, rows);
  const double tan_h = 0.5 * o.width / fx, tan_v = 0.5 * o.height / fx;
  const double height = 1.25 * std::max(sx / tan_h, sy / tan_v);
  const double z = std::max(box.min.z() + height, box.max.z() + 0.25 * std::max(sx, sy));
  std::vector<PinholeCamera> cams;
  for (int k = 0; k < o.count; ++k) {
    const int row = k / cols, c = k % cols;
    const int in_row = std::min(cols, o.count - row * cols);
    const int col = row % 2 ? in_row - 1 - c : c;  // lawnmower: every other row backwards
    const Vec3 eye(at(box.min.x(), wx, col, in_row), at(box.min.y(), wy, row, rows), z);
    cams.push_back(PinholeCamera::look_at(eye, eye - Vec3(0, 0, 1), Vec3(0, 1, 0), fx, fx, (o.width - 1) / 2.0,
                                          (o.height - 1) / 2.0, o.width, o.height));
  }
  return cams;
}

}  // namespace

std::vector<PinholeCamera> make_cameras(const TriangleMesh& mesh, const CameraSetOptions& o) {
  if (o.count < 1) throw Error("camera count must be >= 1");
  if (o.width < 2 || o.height < 2) throw Error("image size must be at least 2x2");
  if (!(o.horizontal_fov_degrees > 1 && o.horizontal_fov_degrees < 170))
    throw Error("horizontal field of view must be in (1, 170) degrees");
  const BoundingBox box = mesh.bounding_box();
  if (box.empty()) throw Error("cannot place cameras around an empty mesh");
  const Vec3 centre = box.center();
  const double radius = 0.5 * box.diagonal();
  const double hfov = o.horizontal_fov_degrees * M_PI / 180.0;
  const double fx = 0.5 * o.width / std::tan(hfov / 2);
  if (o.layout == CameraLayout::Grid) return grid_cameras(box, o, fx);
  const double vfov = 2 * std::atan(0.5 * o.height / fx);
  const double narrow = std::min(hfov, vfov);
  const double distance = radius / std::sin(std::clamp(o.fill, 0.05, 1.0) * narrow / 2);  // always fits

  // (azimuth, elevation) pairs for the layout.
  std::vector<std::pair<double, double>> dirs;
  const double deg = M_PI / 180.0;
  switch (o.layout) {
    case CameraLayout::Ring:
      for (int k = 0; k < o.count; ++k)
        dirs.emplace_back(2 * M_PI * k / o.count, o.elevation_degrees * deg);
      break;
    case CameraLayout::Hemisphere: {
      // Fibonacci spiral on the band 10..75 degrees of elevation.
      const double golden = M_PI * (3.0 - std::sqrt(5.0));
      const double z0 = std::sin(10 * deg), z1 = std::sin(75 * deg);
      for (int k = 0; k < o.count; ++k) {
        const double z = z0 + (z1 - z0) * (k + 0.5) / o.count;
        dirs.emplace_back(golden * k, std::asin(z));
      }
      break;
    }
    case CameraLayout::Orbit: {
      // A drone's orbits at three heights, lower orbits with more shots.
      const double elevations[3] = {15 * deg, 35 * deg, 60 * deg};
      const double share[3] = {0.45, 0.35, 0.2};
      std::mt19937_64 rng(o.seed);
      std::uniform_real_distribution<double> jitter(-0.5, 0.5);
      int used = 0;
      for (int ring = 0; ring < 3; ++ring) {
        const int n = ring < 2 ? std::max(1, int(std::lround(o.count * share[ring])))
                               : o.count - used;
        for (int k = 0; k < n && used < o.count; ++k, ++used)
          dirs.emplace_back(2 * M_PI * (k + 0.3 * jitter(rng)) / n + ring * 0.4,
                            elevations[ring] + 2 * deg * jitter(rng));
      }
      break;
    }
    case CameraLayout::Grid: break;  // above
  }
  // One distance for the whole set: the smallest at which, from every
  // direction, the bounding box's corners fall inside the central `fill`
  // share of the image (bisection between "inside the box" and the
  // bounding-sphere distance, which always fits).
  auto camera_at = [&](const Vec3& dir, double d) {
    return PinholeCamera::look_at(centre + d * dir, centre, Vec3(0, 0, 1), fx, fx,
                                  (o.width - 1) / 2.0, (o.height - 1) / 2.0, o.width, o.height);
  };
  const double fill = std::clamp(o.fill, 0.05, 1.0);
  auto fits = [&](const Vec3& dir, double d) {
    const PinholeCamera cam = camera_at(dir, d);
    for (const Vec3& corner : box.corners()) {
      Vec2 px;
      if (!cam.project(corner, &px)) return false;
      if (std::abs(px.x() - cam.cx) > fill * 0.5 * (o.width - 1) ||
          std::abs(px.y() - cam.cy) > fill * 0.5 * (o.height - 1))
        return false;
    }
    return true;
  };
  std::vector<Vec3> unit_dirs;
  double chosen = 0;
  for (const auto& [az, el] : dirs) {
    const Vec3 dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    unit_dirs.push_back(dir);
    double lo = radius, hi = distance;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (fits(dir, mid) ? hi : lo) = mid;
    }
    chosen = std::max(chosen, hi);
  }
  std::vector<PinholeCamera> cams;
  for (const Vec3& dir : unit_dirs) cams.push_back(camera_at(dir, chosen));
  return cams;
}

}  // namespace meshnbv::synth
