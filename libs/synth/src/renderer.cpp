#include "meshnbv/renderer.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "meshnbv/error.h"

namespace meshnbv {
namespace {

Vec3 background_colour(const RenderInputs& in, const RenderOptions& o, const Vec3& direction) {
  if (!o.textured_background || !in.texture) return o.background;
  const double v = in.texture->fractal_noise(direction * 8.0, 1.0);
  return (o.background * (0.85 + 0.3 * v)).cwiseMin(1.0);
}

// Colour of the first surface along the ray, or the background.
Vec3 trace(const RenderInputs& in, const RenderOptions& o, const Vec3& light, const Ray& ray) {
  RayHit hit;
  if (!in.raycaster->intersect(ray.origin, ray.direction, &hit))
    return background_colour(in, o, ray.direction);
  const TriangleMesh& mesh = *in.mesh;
  const Face& f = mesh.faces[hit.face];
  // The hit point from barycentrics in double precision (Embree's distance is float).
  const Vec3 p = (1.0 - hit.u - hit.v) * mesh.vertices[f[0]] + hit.u * mesh.vertices[f[1]] +
                 hit.v * mesh.vertices[f[2]];
  Vec3 n = mesh.face_normal(hit.face);
  if (n.dot(ray.direction) > 0) n = -n;  // two-sided
  const double shade = o.ambient + o.diffuse * std::max(0.0, n.dot(light));
  if (in.face_colors) {
    const Rgb8& c = (*in.face_colors)[std::size_t(hit.face)];
    return Vec3(c[0], c[1], c[2]) / 255.0 * shade;
  }
  const int material = in.materials ? int((*in.materials)[hit.face]) : 0;
  return in.texture->albedo(p, n, material) * shade;
}

}  // namespace

Image render(const RenderInputs& in, const PinholeCamera& camera, const RenderOptions& o,
             std::vector<float>* depth, const ProgressCallback& progress) {
  if (!in.mesh || !in.raycaster || !(in.texture || in.face_colors))
    throw Error("render: missing mesh, ray caster, or texture/face colours");
  if (in.face_colors && in.face_colors->size() != in.mesh->num_faces())
    throw Error("render: face colours do not match the face count");
  if (in.materials && in.materials->size() != in.mesh->num_faces())
    throw Error("render: material ids do not match the face count");
  camera.check("render camera");
  if (o.samples_per_pixel < 1) throw Error("render: samples_per_pixel must be >= 1");
  const int n = std::max(1, int(std::floor(std::sqrt(double(o.samples_per_pixel)) + 1e-9)));
  const Vec3 light = o.light_direction.normalized();
  const Vec3 forward = camera.forward();
  const int W = camera.width, H = camera.height;
  Image image(W, H, 3);
  if (depth) depth->assign(std::size_t(W) * H, std::numeric_limits<float>::quiet_NaN());

  auto render_row = [&](int y) {
    for (int x = 0; x < W; ++x) {
      Vec3 sum = Vec3::Zero();
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          const Vec2 pixel(x - 0.5 + (sx + 0.5) / n, y - 0.5 + (sy + 0.5) / n);
          sum += trace(in, o, light, camera.viewing_ray(pixel));
        }
      if (depth) {
        const Ray ray = camera.viewing_ray(Vec2(x, y));
        RayHit hit;
        if (in.raycaster->intersect(ray.origin, ray.direction, &hit))
          (*depth)[std::size_t(y) * W + x] = float(hit.distance * ray.direction.dot(forward));
      }
      const Vec3 c = (sum / double(n * n)).cwiseMax(0.0).cwiseMin(1.0);
      std::uint8_t* px = image.pixel(x, y);
      for (int k = 0; k < 3; ++k) px[k] = std::uint8_t(std::lround(c[k] * 255.0));
    }
  };
  // Bands of rows in parallel; progress and cancellation between bands, on
  // the calling thread.
  const int band = 32;
  for (int y0 = 0; y0 < H; y0 += band) {
    const int y1 = std::min(H, y0 + band);
    tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& r) {
      for (int y = r.begin(); y < r.end(); ++y) render_row(y);
    });
    report_progress(progress, double(y1) / H, "render");
  }
  return image;
}

}  // namespace meshnbv
