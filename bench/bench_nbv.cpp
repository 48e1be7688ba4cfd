// Next-view suggestion speed on the synthetic building (14k faces, 12
// existing views, K = 10 worst faces): candidate evaluations per second on
// 1 and 2 threads for the paper's energy and the whole-mesh one
// (energy = reconstructability, 2048 clusters), and the sampled and refined
// modes end to end for both.
#include <benchmark/benchmark.h>

#include <filesystem>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "meshnbv/gain.h"
#include "meshnbv/planner.h"
#include "meshnbv/pri.h"
#include "meshnbv/synth/project.h"

using namespace meshnbv;

namespace {
struct Fixture {
  synth::SynthProject project;
  std::vector<float> pri;
  Fixture() {
    synth::SynthOptions o;
    o.scene = "building";
    o.cameras.count = 12;
    o.cameras.layout = synth::CameraLayout::Orbit;
    o.cameras.width = 320;
    o.cameras.height = 240;
    o.overwrite = true;
    const std::string dir = (std::filesystem::temp_directory_path() / "meshnbv_bench_nbv").string();
    project = synth::write_synthetic_project(o, dir);
    pri = compute_pri(project.scene).pri;
  }
};
Fixture& fixture() {
  static Fixture f;
  return f;
}
}  // namespace

// The energy of many candidate poses (the sampled set, 1536 poses).
static void BM_CandidateEvaluations(benchmark::State& state) {
  Fixture& f = fixture();
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  const TriangleMesh& mesh = f.project.scene.mesh;
  const RayCaster caster(mesh);
  const WorstRegion region = worst_region(mesh, f.pri, 10);
  std::vector<PinholeCamera> cams;
  std::vector<Vec3> existing;
  for (const auto& v : f.project.scene.views) cams.push_back(v.camera), existing.push_back(v.camera.center());
  const SafetyChecker safety(mesh, caster, 0.05 * mesh.bounding_box().diagonal());
  const CandidateSet set = sample_candidates(region, most_common_intrinsics(cams), mean_up(cams),
                                             median_viewing_distance(cams, caster, region.centroid),
                                             safety, SamplingOptions{});
  const EnergyEvaluator energy(mesh, caster, region, existing, EnergyOptions{});
  std::vector<double> out(set.cameras.size());
  for (auto _ : state) {
    tbb::parallel_for(std::size_t(0), set.cameras.size(),
                      [&](std::size_t i) { out[i] = energy.evaluate(set.cameras[i]).total; });
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["evaluations_per_s"] = benchmark::Counter(
      double(set.cameras.size()) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["worst_vertices"] = double(region.vertices.size());
}
BENCHMARK(BM_CandidateEvaluations)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole-mesh energy (gain.h) of the same 1536 poses: every cluster's
// visibility and pairs with the views that already see it.
static void BM_GainEvaluations(benchmark::State& state) {
  Fixture& f = fixture();
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  const TriangleMesh& mesh = f.project.scene.mesh;
  const RayCaster caster(mesh);
  const WorstRegion region = worst_region(mesh, f.pri, 10);
  std::vector<PinholeCamera> cams;
  for (const auto& v : f.project.scene.views) cams.push_back(v.camera);
  const SafetyChecker safety(mesh, caster, 0.05 * mesh.bounding_box().diagonal());
  const CandidateSet set = sample_candidates(region, most_common_intrinsics(cams), mean_up(cams),
                                             median_viewing_distance(cams, caster, region.centroid),
                                             safety, SamplingOptions{});
  const GainEvaluator gain(mesh, caster, f.pri, cams, GainOptions{});
  std::vector<double> out(set.cameras.size());
  for (auto _ : state) {
    tbb::parallel_for(std::size_t(0), set.cameras.size(),
                      [&](std::size_t i) { out[i] = gain.evaluate(set.cameras[i]).total; });
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["evaluations_per_s"] = benchmark::Counter(
      double(set.cameras.size()) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["clusters"] = double(gain.num_clusters());
}
BENCHMARK(BM_GainEvaluations)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// suggest_views end to end (ray caster and safety structures included).
static void BM_Suggest(benchmark::State& state) {
  Fixture& f = fixture();
  SuggestOptions o;
  o.mode = state.range(0) % 2 == 0 ? CandidateMode::Sampled : CandidateMode::Refined;
  o.energy_kind = state.range(0) < 2 ? EnergyKind::Paper : EnergyKind::Reconstructability;
  o.threads = 2;
  std::size_t evaluated = 0;
  for (auto _ : state) {
    const SuggestResult r = suggest_views(f.project.scene, f.pri, o);
    evaluated = r.candidates_evaluated;
    benchmark::DoNotOptimize(r.suggestions.data());
  }
  state.SetLabel(std::string(o.mode == CandidateMode::Sampled ? "sampled" : "refined") + ", " +
                 energy_kind_name(o.energy_kind));
  state.counters["candidate_evaluations"] = double(evaluated);
}
BENCHMARK(BM_Suggest)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
