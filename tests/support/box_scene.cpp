#include "box_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <tuple>

#include "meshnbv/io/mesh_io.h"
#include "meshnbv/io/scene_io.h"

namespace meshnbv::test {
namespace {

// Deterministic solid texture in [0, 1] from the 3-D position.
double texture(const Vec3& p) {
  const double s = 0.5 + 0.2 * std::sin(23.0 * p.x() + 5.0 * p.z()) * std::cos(19.0 * p.y()) +
                   0.15 * std::sin(61.0 * (p.x() + p.y() + p.z()));
  const int checker = (int(std::floor(p.x() * 8)) + int(std::floor(p.y() * 8)) +
                       int(std::floor(p.z() * 8))) & 1;
  return std::clamp(s + (checker ? 0.12 : -0.12), 0.0, 1.0);
}

// Slab intersection; returns distance and outward normal of the hit side.
bool intersect_box(const Vec3& min, const Vec3& max, const Ray& ray, double* t_hit, Vec3* normal) {
  double t0 = 0, t1 = INFINITY;
  int axis = -1;
  double sign = 0;
  for (int a = 0; a < 3; ++a) {
    const double inv = 1.0 / ray.direction[a];
    double tn = (min[a] - ray.origin[a]) * inv, tf = (max[a] - ray.origin[a]) * inv;
    double side = -1;
    if (tn > tf) {
      std::swap(tn, tf);
      side = 1;
    }
    if (tn > t0) {
      t0 = tn;
      axis = a;
      sign = side;
    }
    t1 = std::min(t1, tf);
    if (t0 > t1) return false;
  }
  if (axis < 0) return false;  // origin inside the box
  *t_hit = t0;
  *normal = Vec3::Zero();
  (*normal)[axis] = sign;
  return true;
}

}  // namespace

Scene make_box_scene(const BoxSceneOptions& o) {
  Scene scene;
  TriangleMesh& m = scene.mesh;
  const int n = o.subdivisions;
  // Each side: a (n+1)^2 vertex grid, triangles wound so normals point out.
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int base = static_cast<int>(m.vertices.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          Vec3 p;
          p[axis] = side ? o.max[axis] : o.min[axis];
          p[u] = o.min[u] + (o.max[u] - o.min[u]) * i / n;
          p[v] = o.min[v] + (o.max[v] - o.min[v]) * j / n;
          m.vertices.push_back(p);
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
          if (side)
            m.faces.push_back({a, b, d}), m.faces.push_back({a, d, c});
          else
            m.faces.push_back({a, d, b}), m.faces.push_back({a, c, d});
        }
    }
  }
  // Weld the sides' shared edge vertices (computed by the same formula, so
  // bitwise equal) to make the box closed and manifold.
  std::map<std::tuple<double, double, double>, int> index;
  std::vector<int> remap(m.vertices.size());
  std::vector<Vec3> welded;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& p = m.vertices[i];
    auto [it, inserted] = index.try_emplace({p.x(), p.y(), p.z()}, int(welded.size()));
    if (inserted) welded.push_back(p);
    remap[i] = it->second;
  }
  m.vertices = welded;
  for (auto& f : m.faces)
    for (int& i : f) i = remap[i];
  const Vec3 centre = 0.5 * (o.min + o.max);
  const double f = 0.9 * o.width;
  for (int k = 0; k < o.views; ++k) {
    const double angle = 2.0 * M_PI * k / o.views + 0.3;
    const Vec3 eye = centre + Vec3(o.ring_radius * std::cos(angle), o.ring_radius * std::sin(angle),
                                   o.ring_height);
    View view;
    char label[32];
    std::snprintf(label, sizeof(label), "view_%02d", k);
    view.label = label;
    view.camera = PinholeCamera::look_at(eye, centre, {0, 0, 1}, f, f, (o.width - 1) / 2.0,
                                         (o.height - 1) / 2.0, o.width, o.height);
    scene.views.push_back(view);
  }
  return scene;
}

Image render_box(const BoxSceneOptions& o, const PinholeCamera& camera) {
  Image image(camera.width, camera.height, 3);
  const Vec3 light = Vec3(0.4, -0.3, 0.85).normalized();
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      std::uint8_t* px = image.pixel(x, y);
      // 2x2 supersampling against aliasing.
      double rgb[3] = {0, 0, 0};
      for (int s = 0; s < 4; ++s) {
        const Vec2 pixel(x - 0.25 + 0.5 * (s & 1), y - 0.25 + 0.5 * (s >> 1));
        const Ray ray = camera.viewing_ray(pixel);
        double t;
        Vec3 normal;
        if (!intersect_box(o.min, o.max, ray, &t, &normal)) {
          rgb[0] += 0.15, rgb[1] += 0.18, rgb[2] += 0.22;  // plain background
          continue;
        }
        const double shade = 0.35 + 0.65 * std::max(0.0, normal.dot(light));
        const double albedo = texture(ray.origin + t * ray.direction);
        rgb[0] += shade * albedo;
        rgb[1] += shade * (0.8 * albedo + 0.1);
        rgb[2] += shade * (0.6 * albedo + 0.15);
      }
      for (int c = 0; c < 3; ++c)
        px[c] = static_cast<std::uint8_t>(std::lround(std::clamp(rgb[c] / 4.0, 0.0, 1.0) * 255));
    }
  return image;
}

void write_box_project(const std::string& folder, const BoxSceneOptions& o) {
  namespace fs = std::filesystem;
  Scene scene = make_box_scene(o);
  fs::create_directories(fs::path(folder) / "images");
  const std::string mesh_file = (fs::path(folder) / "box.ply").string();
  io::PlyWriteOptions ply;
  ply.binary = false;  // small and readable in the repository
  io::write_ply(scene.mesh, mesh_file, ply);
  for (auto& view : scene.views) {
    view.image_path = (fs::path(folder) / "images" / (view.label + ".png")).string();
    render_box(o, view.camera).save(view.image_path);
  }
  io::write_mlp(scene, (fs::path(folder) / "box.mlp").string(), mesh_file, true);
}

}  // namespace meshnbv::test
