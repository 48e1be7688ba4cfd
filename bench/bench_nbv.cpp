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

namespace {
// The sampled candidate set (1536 poses) around the K = 10 worst faces,
// with the structures both energies need.
struct Sampled {
  const TriangleMesh& mesh;
  RayCaster caster;
  WorstRegion region;
  std::vector<PinholeCamera> cams;
  std::vector<Vec3> existing;
  CandidateSet set;
  explicit Sampled(const Fixture& f) : mesh(f.project.scene.mesh), caster(mesh) {
    region = worst_region(mesh, f.pri, 10);
    for (const auto& v : f.project.scene.views) cams.push_back(v.camera), existing.push_back(v.camera.center());
    const SafetyChecker safety(mesh, caster, 0.05 * mesh.bounding_box().diagonal());
    set = sample_candidates(region, most_common_intrinsics(cams), mean_up(cams),
                            median_viewing_distance(cams, caster, region.centroid), safety, SamplingOptions{});
  }
};

// Times `energy(camera)` over the whole set on state.range(0) threads.
template <class Energy>
void time_evaluations(benchmark::State& state, const CandidateSet& set, Energy energy) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  std::vector<double> out(set.cameras.size());
  for (auto _ : state) {
    tbb::parallel_for(std::size_t(0), set.cameras.size(), [&](std::size_t i) { out[i] = energy(set.cameras[i]); });
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["evaluations_per_s"] = benchmark::Counter(
      double(set.cameras.size()) * state.iterations(), benchmark::Counter::kIsRate);
}
}  // namespace

// The paper's energy of the sampled set.
static void BM_CandidateEvaluations(benchmark::State& state) {
  const Sampled s(fixture());
  const EnergyEvaluator energy(s.mesh, s.caster, s.region, s.existing, EnergyOptions{});
  time_evaluations(state, s.set, [&](const PinholeCamera& c) { return energy.evaluate(c).total; });
  state.counters["worst_vertices"] = double(s.region.vertices.size());
}
BENCHMARK(BM_CandidateEvaluations)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole-mesh energy (gain.h) of the same poses: every cluster's
// visibility and pairs with the views that already see it.
static void BM_GainEvaluations(benchmark::State& state) {
  const Sampled s(fixture());
  const GainEvaluator gain(s.mesh, s.caster, fixture().pri, s.cams, GainOptions{});
  time_evaluations(state, s.set, [&](const PinholeCamera& c) { return gain.evaluate(c).total; });
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
