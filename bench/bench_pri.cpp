// PRI speed (issue 4) on a synthetic city of > 200,000 faces seen by 20
// views at 640x480, generated once per process into a temporary folder.
//
//  BM_Pri/threads/views/spp/simd compute_pri with max_views_per_face = views
//                                and samples_per_side = spp (0 = automatic),
//                                the sampling kernels at simd = 0 (scalar)
//                                or 1 (the widest this processor runs; the
//                                run's label names it).
//                                The benchmark time is the sampling +
//                                comparison phase: each iteration times the
//                                view selection alone (select_pri_views, the
//                                first phase of compute_pri) and then compute_pri, and
//                                reports the difference. end_to_end_s and
//                                select_s give both parts; e2e_* rates are
//                                over the whole compute_pri call.
//  BM_PriColdCache/...           compute_pri end to end with the scene's
//                                image cache emptied before each call.
//  BM_Baseline/threads/views     the paper's OpenCV warping method on the
//                                same faces and views, r = 8 (time excludes
//                                visibility: the view lists are given), on
//                                every 4th face.
//  BM_BilinearPeak/threads/pattern  bilinear sampling at precomputed
//                                coordinates in a tight loop: random (generic
//                                and inline sampler) and triangle lattices,
//                                scalar (0-2) and vectorised (3-4).
//
// Counters: faces_per_s (all faces of the mesh / all faces of the subset)
// and samples_per_s (sum over those faces of (r+1)(r+2)/2 x views), over
// wall time; BM_Pri's cpu_samples_per_s is over CPU time (for one thread
// comparable with the cpu_time of BM_Baseline and BM_BilinearPeak, which
// then run on the main thread only).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <random>

#include "meshnbv/image.h"
#include "meshnbv/pri.h"
#include "meshnbv/sampling.h"
#include "meshnbv/synth/project.h"
#include "pri_baseline.h"

using namespace meshnbv;
namespace fs = std::filesystem;

namespace {

constexpr double kEdgeLength = 0.38;  // metres: ~219k faces for the city
constexpr std::size_t kMinFaces = 200000;
constexpr std::size_t kBaselineStride = 4;  // the baseline runs on every 4th face
constexpr int kBaselineR = 8;

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU seconds of the calling thread (1 thread: all the work runs on it,
// task_arena(1)) or of the process (2 threads): unlike wall time, they do
// not grow while the machine's other load keeps the benchmark waiting.
double cpu_s(bool process) {
  timespec t{};
  clock_gettime(process ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double lattice(int r) { return double(r + 1) * double(r + 2) / 2.0; }

struct Fixture {
  fs::path folder;
  synth::SynthProject project;
  std::vector<std::size_t> subset;  // faces of the baseline
  std::vector<cv::Mat> grey;        // baseline planes
  struct PerViews {
    bench::Selection selection;
    std::vector<float> core_pri;  // compute_pri, r = 8
  };
  std::map<int, PerViews> per_views;
  std::mutex mutex;

  Fixture() {
    folder = fs::temp_directory_path() / ("meshnbv_bench_pri_" + std::to_string(getpid()));
    synth::SynthOptions o;
    o.scene = "city";
    o.generator.edge_length = kEdgeLength;
    o.cameras.layout = synth::CameraLayout::Hemisphere;
    o.cameras.count = 20;
    o.cameras.width = 640;
    o.cameras.height = 480;
    synth::Degradation noise;
    noise.kind = synth::DegradationKind::Noise;
    noise.strength = 0.002;
    noise.radius = 0.15;
    o.degradations = {noise};
    o.overwrite = true;
    const double t0 = now_s();
    project = synth::write_synthetic_project(o, folder.string());
    const std::size_t F = scene().mesh.num_faces();
    std::fprintf(stderr, "bench_pri: city, edge %.2f m: %zu faces, %zu vertices, %zu views %dx%d (%.1f s) in %s\n",
                 kEdgeLength, F, scene().mesh.num_vertices(), scene().views.size(), o.cameras.width,
                 o.cameras.height, now_s() - t0, folder.c_str());
    if (F < kMinFaces) {
      std::fprintf(stderr, "bench_pri: the scene has fewer than %zu faces\n", kMinFaces);
      std::exit(1);
    }
    for (std::size_t i = 0; i < scene().views.size(); ++i) scene().image(i);  // warm the cache
    for (std::size_t f = 0; f < F; f += kBaselineStride) subset.push_back(f);
    cv::setNumThreads(0);  // OpenCV's own threads stay out of the baseline
  }
  ~Fixture() {
    std::error_code ec;
    fs::remove_all(folder, ec);
  }
  const Scene& scene() const { return project.scene; }

  // View lists for max_views_per_face = views, checked against compute_pri.
  const PerViews& views(int v) {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = per_views.find(v);
    if (it != per_views.end()) return it->second;
    PriOptions o;
    o.max_views_per_face = v;
    o.samples_per_side = kBaselineR;
    o.edge_margin = 0;  // the baseline warps the whole triangle: compare like with like
    PerViews p;
    p.selection = select_pri_views(scene(), o);
    const PriResult core = compute_pri(scene(), o);
    std::size_t mismatches = 0;
    for (std::size_t f = 0; f < core.pri_views.size(); ++f)
      mismatches += std::size_t(core.pri_views[f]) != p.selection.faces[f].views.size();
    if (mismatches) {
      std::fprintf(stderr,
                   "bench_pri: select_pri_views and compute_pri's pri_views disagree on %zu "
                   "faces\n",
                   mismatches);
      std::exit(1);
    }
    p.core_pri = core.pri;
    if (grey.empty()) grey = bench::grey_planes(scene(), p.selection);
    return per_views.emplace(v, std::move(p)).first->second;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

double samples_of(const bench::Selection& s, int r_fixed, const std::vector<std::size_t>* faces) {
  double n = 0;
  auto add = [&](std::size_t f) {
    n += lattice(r_fixed > 0 ? r_fixed : s.faces[f].samples_per_side) * double(s.faces[f].views.size());
  };
  if (faces) for (std::size_t f : *faces) add(f);
  else for (std::size_t f = 0; f < s.faces.size(); ++f) add(f);
  return n;
}

}  // namespace

// Sampling + comparison of compute_pri (= compute_pri - view selection).
static void BM_Pri(benchmark::State& state) {
  Fixture& fx = fixture();
  PriOptions o;
  o.threads = int(state.range(0));
  o.max_views_per_face = int(state.range(1));
  o.samples_per_side = int(state.range(2));
  (void)fx.views(o.max_views_per_face);  // checks select_pri_views against compute_pri
  const SimdLevel simd = set_simd_level(state.range(3) ? simd_supported() : SimdLevel::scalar);
  state.SetLabel(simd_name(simd));
  const double F = double(fx.scene().mesh.num_faces());
  const bool process = o.threads > 1;
  double select = 0, total = 0, samples = 0, cpu = 0;
  std::size_t observed = 0;
  for (auto _ : state) {
    const double c0 = cpu_s(process), t0 = now_s();
    const bench::Selection s = select_pri_views(fx.scene(), o);
    const double c1 = cpu_s(process), t1 = now_s();
    const PriResult r = compute_pri(fx.scene(), o);
    const double c2 = cpu_s(process), t2 = now_s();
    observed = r.observed;
    samples = samples_of(s, o.samples_per_side, nullptr);  // automatic r: the per-face rule
    select += t1 - t0;
    total += t2 - t1;
    cpu += (c2 - c1) - (c1 - c0);
    state.SetIterationTime(std::max(1e-6, (t2 - t1) - (t1 - t0)));
  }
  const double it = double(state.iterations());
  state.counters["faces_per_s"] = benchmark::Counter(F * it, benchmark::Counter::kIsRate);
  state.counters["samples_per_s"] = benchmark::Counter(samples * it, benchmark::Counter::kIsRate);
  state.counters["end_to_end_s"] = total / it;
  state.counters["select_s"] = select / it;
  state.counters["e2e_faces_per_s"] = F * it / total;
  state.counters["e2e_samples_per_s"] = samples * it / total;
  state.counters["samples_per_face"] = samples / F;
  state.counters["observed"] = double(observed);
  // Sampling + comparison per CPU second (all threads): robust to other load.
  state.counters["cpu_samples_per_s"] = samples * it / cpu;
  set_simd_level(simd_supported());
}
BENCHMARK(BM_Pri)
    ->ArgNames({"threads", "views", "spp", "simd"})
    ->Args({1, 5, 8, 1})->Args({1, 10, 8, 1})->Args({1, 20, 8, 1})
    ->Args({2, 5, 8, 1})->Args({2, 10, 8, 1})->Args({2, 20, 8, 1})
    ->Args({2, 10, 0, 1})
    ->Args({1, 5, 8, 0})->Args({1, 20, 8, 0})->Args({2, 5, 8, 0})->Args({2, 20, 8, 0})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);

// compute_pri end to end with every image decoded again (PNG).
static void BM_PriColdCache(benchmark::State& state) {
  Fixture& fx = fixture();
  PriOptions o;
  o.threads = int(state.range(0));
  o.max_views_per_face = int(state.range(1));
  o.samples_per_side = int(state.range(2));
  const auto& pv = fx.views(o.max_views_per_face);
  const double F = double(fx.scene().mesh.num_faces());
  const double samples = samples_of(pv.selection, o.samples_per_side, nullptr);
  for (auto _ : state) {
    state.PauseTiming();
    fx.scene().images->clear();
    state.ResumeTiming();
    benchmark::DoNotOptimize(compute_pri(fx.scene(), o).observed);
  }
  const double it = double(state.iterations());
  state.counters["faces_per_s"] = benchmark::Counter(F * it, benchmark::Counter::kIsRate);
  state.counters["samples_per_s"] = benchmark::Counter(samples * it, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PriColdCache)
    ->ArgNames({"threads", "views", "spp"})
    ->Args({2, 10, 8})
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);

// The paper's method: affine warp of each (face, view) + masked SSD of every pair.
static void BM_Baseline(benchmark::State& state) {
  Fixture& fx = fixture();
  const int threads = int(state.range(0)), views = int(state.range(1));
  const auto& pv = fx.views(views);
  std::vector<float> pri(fx.scene().mesh.num_faces(), std::numeric_limits<float>::quiet_NaN());
  for (auto _ : state)
    bench::baseline_pri(fx.scene().mesh, pv.selection, fx.grey, fx.subset, kBaselineR, threads, &pri);
  const double it = double(state.iterations());
  const double samples = samples_of(pv.selection, kBaselineR, &fx.subset);
  state.counters["faces_per_s"] = benchmark::Counter(double(fx.subset.size()) * it, benchmark::Counter::kIsRate);
  state.counters["samples_per_s"] = benchmark::Counter(samples * it, benchmark::Counter::kIsRate);
  state.counters["samples_per_face"] = samples / double(fx.subset.size());
  // Agreement with compute_pri on the same faces (Pearson correlation and
  // median relative difference of the PRI values).
  std::vector<double> a, b, rel;
  for (std::size_t f : fx.subset)
    if (std::isfinite(pri[f]) && std::isfinite(pv.core_pri[f])) {
      a.push_back(pri[f]);
      b.push_back(pv.core_pri[f]);
      if (pv.core_pri[f] > 0) rel.push_back(std::abs(pri[f] - pv.core_pri[f]) / pv.core_pri[f]);
    }
  double ma = 0, mb = 0, sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) ma += a[k], mb += b[k];
  ma /= double(a.size()), mb /= double(b.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    sab += (a[k] - ma) * (b[k] - mb), saa += (a[k] - ma) * (a[k] - ma), sbb += (b[k] - mb) * (b[k] - mb);
  std::nth_element(rel.begin(), rel.begin() + std::ptrdiff_t(rel.size() / 2), rel.end());
  state.counters["corr_with_core"] = sab / std::sqrt(saa * sbb);
  state.counters["median_rel_diff"] = rel.empty() ? 0.0 : rel[rel.size() / 2];
}
BENCHMARK(BM_Baseline)
    ->ArgNames({"threads", "views"})
    ->Args({1, 5})->Args({1, 10})->Args({1, 20})
    ->Args({2, 5})->Args({2, 10})->Args({2, 20})
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);

// Peak of bilinear sampling on this machine, three access patterns over
// the luminance plane of a view (2^20 precomputed coordinates, tight loop):
//   pattern 0: FloatImage::sample (any channel count) at random coordinates;
//   pattern 1: FloatImage::sample_gray (inline, one channel) at random coordinates;
//   pattern 2: sample_gray on the lattices of 8-pixel triangles at random
//              places (45 samples each, r = 8): the cache-friendly access
//              of PRI, at the fastest pattern;
//   pattern 3: sample_gray_points (the widest kernel this processor runs;
//              the label names it) at the random coordinates, 64 at a call;
//   pattern 4: sample_gray_points on the lattices, one call per lattice.
// The report takes the fastest pattern as the peak (bench/pri_table.py).
static void BM_BilinearPeak(benchmark::State& state) {
  Fixture& fx = fixture();
  const int threads = int(state.range(0)), pattern = int(state.range(1));
  const FloatImage plane = FloatImage::luminance_of(*fx.scene().image(0));
  const std::size_t n = std::size_t(1) << 20;
  std::vector<double> xy(2 * n);
  std::mt19937_64 rng(7);
  const bool random = pattern == 0 || pattern == 1 || pattern == 3;
  if (random) {
    std::uniform_real_distribution<double> ux(0.0, plane.width() - 1.0), uy(0.0, plane.height() - 1.0);
    for (std::size_t k = 0; k < n; ++k) xy[2 * k] = ux(rng), xy[2 * k + 1] = uy(rng);
  } else {
    std::uniform_real_distribution<double> ux(0.0, plane.width() - 10.0), uy(0.0, plane.height() - 10.0),
        edge(-1.0, 1.0);
    std::size_t k = 0;
    while (k < n) {
      // A triangle with corners near (0,0), (8,0), (0,8) from a random origin.
      const double x0 = ux(rng), y0 = uy(rng);
      const double ex = 8 + 0.5 * edge(rng), ey = 8 + 0.5 * edge(rng);
      for (int a = 0; a <= kBaselineR && k < n; ++a)
        for (int b = 0; b <= kBaselineR - a && k < n; ++b, ++k) {
          xy[2 * k] = x0 + ex * a / kBaselineR + 0.3 * b / kBaselineR;
          xy[2 * k + 1] = y0 + ey * b / kBaselineR + 0.2 * a / kBaselineR;
        }
    }
  }
  // The vector kernels read the coordinates as two arrays.
  std::vector<double> x(n), y(n);
  std::vector<float> vals(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = xy[2 * k], y[k] = xy[2 * k + 1];
  if (pattern >= 3) state.SetLabel(simd_name(simd_level()));
  tbb::task_arena arena(threads);
  // Whole lattices per thread.
  const std::size_t per_lattice = std::size_t(lattice(kBaselineR));
  const std::size_t chunk = (n / per_lattice + std::size_t(threads) - 1) / std::size_t(threads) * per_lattice;
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, n, chunk),
          [&](const auto& r) {
            float sum = 0;
            if (pattern >= 3) {
              // A call per 64 points or per lattice, as PRI calls it.
              const std::size_t call = pattern == 3 ? 64 : lattice(kBaselineR);
              for (std::size_t k = r.begin(); k < r.end(); k += call) {
                const std::size_t m = std::min(call, r.end() - k);
                if (sample_gray_points(plane, &x[k], &y[k], m, &vals[k])) sum += vals[k];
              }
            } else {
              for (std::size_t k = r.begin(); k < r.end(); ++k) {
                float v;
                if (pattern == 0 ? plane.sample(xy[2 * k], xy[2 * k + 1], &v)
                                 : plane.sample_gray(xy[2 * k], xy[2 * k + 1], &v))
                  sum += v;
              }
            }
            benchmark::DoNotOptimize(sum);
          },
          tbb::simple_partitioner());
    });
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(n) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BilinearPeak)
    ->ArgNames({"threads", "pattern"})
    ->Args({1, 0})->Args({1, 1})->Args({1, 2})->Args({1, 3})->Args({1, 4})
    ->Args({2, 0})->Args({2, 1})->Args({2, 2})->Args({2, 3})->Args({2, 4})
    ->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
