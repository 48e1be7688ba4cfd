// Renderer and ray caster speed on the synthetic building (640x480).
// Counters: rays per second (single query loop on one thread) and images
// per second (the parallel renderer, all threads).
#include <benchmark/benchmark.h>

#include "meshnbv/raycaster.h"
#include "meshnbv/renderer.h"
#include "meshnbv/synth/generators.h"

using namespace meshnbv;

namespace {
struct Fixture {
  TriangleMesh mesh = synth::make_building();
  RayCaster caster{mesh};
  SolidTexture texture{1};
  PinholeCamera camera = [this] {
    synth::CameraSetOptions o;
    o.count = 4;
    return synth::make_cameras(mesh, o)[1];
  }();
};
Fixture& fixture() {
  static Fixture f;
  return f;
}
}  // namespace

// Primary rays through every pixel centre, nearest hit, one thread.
static void BM_RaysNearestHit(benchmark::State& state) {
  Fixture& f = fixture();
  std::vector<Ray> rays;
  for (int y = 0; y < f.camera.height; ++y)
    for (int x = 0; x < f.camera.width; ++x) rays.push_back(f.camera.viewing_ray(Vec2(x, y)));
  std::size_t hits = 0;
  for (auto _ : state) {
    for (const Ray& r : rays) {
      RayHit h;
      hits += f.caster.intersect(r.origin, r.direction, &h);
    }
  }
  benchmark::DoNotOptimize(hits);
  state.counters["rays_per_s"] =
      benchmark::Counter(double(rays.size()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RaysNearestHit)->Unit(benchmark::kMillisecond)->UseRealTime();

// Occlusion (shadow-ray style) queries towards the camera, one thread.
static void BM_RaysOccluded(benchmark::State& state) {
  Fixture& f = fixture();
  const Vec3 c = f.camera.center();
  std::vector<Vec3> targets;
  for (std::size_t i = 0; i < f.mesh.num_vertices(); ++i) targets.push_back(f.mesh.vertices[i]);
  std::size_t clear = 0;
  for (auto _ : state)
    for (const Vec3& t : targets) clear += f.caster.segment_clear(c, t, 1e-4, 1e-6);
  benchmark::DoNotOptimize(clear);
  state.counters["rays_per_s"] =
      benchmark::Counter(double(targets.size()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RaysOccluded)->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole images at 640x480, supersampling 1 and 4.
static void BM_RenderImage(benchmark::State& state) {
  Fixture& f = fixture();
  RenderOptions o;
  o.samples_per_pixel = int(state.range(0));
  const RenderInputs in{&f.mesh, &f.caster, &f.texture, f.mesh.face_attribute(synth::kMaterialAttribute)};
  for (auto _ : state) benchmark::DoNotOptimize(render(in, f.camera, o));
  state.counters["images_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays_per_s"] = benchmark::Counter(
      double(state.iterations()) * 640 * 480 * o.samples_per_pixel, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderImage)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
