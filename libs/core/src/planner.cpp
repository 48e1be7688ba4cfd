#include "meshnbv/planner.h"
#include "meshnbv/enum_names.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "meshnbv/options.h"
#include "meshnbv/error.h"

namespace meshnbv {

constexpr detail::EnumTable<CandidateMode, 3> kCandidateModes = {
    {"given", CandidateMode::Given},
    {"sampled", CandidateMode::Sampled},
    {"refined", CandidateMode::Refined},
};

CandidateMode parse_candidate_mode(const std::string& name) {
  return detail::parse_enum(name, kCandidateModes, "candidate mode");
}

std::string candidate_mode_name(CandidateMode mode) {
  return detail::enum_name(mode, kCandidateModes);
}

void SuggestOptions::check() const {
  // The ranges are the option table's (options.h): one place for every
  // front end. The table covers the nested energy, sampling and refine
  // fields too; only what it does not hold is checked besides.
  check_options(*this, suggest_option_table());
  energy.visibility.check();
  sampling.check_not_in_table();
  refine.check_not_in_table();
}

namespace {

struct Scored {
  PinholeCamera camera;
  std::string label;
  EnergyTerms energy;
  std::size_t given_index = std::size_t(-1);
};

bool ranked_before(const Scored& a, const Scored& b) { return a.energy.total > b.energy.total; }

// Energies in parallel (or by the caller's scorer, for the paper's
// energy); stable order: best energy first, ties by input order. `gain`
// non-null: the whole-mesh energy instead of `e`.
std::vector<Scored> score(const std::vector<Scored>& in, const EnergyEvaluator& e, const GainEvaluator* gain,
                          const TriangleMesh& mesh, const EnergyOptions& options,
                          const CandidateScorer& scorer) {
  std::vector<Scored> out = in;
  if (gain) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size()), [&](const auto& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) out[i].energy = gain->evaluate(out[i].camera);
    });
  } else if (scorer) {
    std::vector<PinholeCamera> cameras;
    cameras.reserve(out.size());
    for (const Scored& s : out) cameras.push_back(s.camera);
    const std::vector<EnergyTerms> energies = scorer(mesh, e, options, cameras);
    if (energies.size() != out.size())
      throw Error("the candidate scorer returned " + std::to_string(energies.size()) + " energies for " +
                  std::to_string(out.size()) + " candidates");
    for (std::size_t i = 0; i < out.size(); ++i) out[i].energy = energies[i];
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size()), [&](const auto& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) out[i].energy = e.evaluate(out[i].camera);
    });
  }
  std::stable_sort(out.begin(), out.end(), ranked_before);
  return out;
}

Vec3 look_at_point(const PinholeCamera& cam, const RayCaster& caster, const Vec3& region_centroid) {
  RayHit hit;
  if (caster.intersect(cam.center(), cam.forward(), &hit)) return cam.center() + hit.distance * cam.forward();
  return cam.center() + cam.forward() * (region_centroid - cam.center()).norm();
}

std::vector<PinholeCamera> existing_cameras(const Scene& scene) {
  std::vector<PinholeCamera> cams;
  for (const auto& v : scene.views)
    if (v.has_image() && v.used) cams.push_back(v.camera);
  if (cams.empty())
    throw Error("no existing view (with an image) to take distances, intrinsics and parallax from");
  return cams;
}

// Given mode's candidates: `given`, or else the scene's views without an
// image or marked unused.
std::vector<Scored> given_pool(const Scene& scene, const std::vector<View>& given) {
  const std::vector<View>* src = &given;
  std::vector<View> own;
  if (given.empty()) {
    for (const auto& v : scene.views)
      if (!v.has_image() || !v.used) own.push_back(v);
    src = &own;
  }
  std::vector<Scored> pool;
  for (std::size_t i = 0; i < src->size(); ++i) {
    (*src)[i].camera.check("candidate '" + (*src)[i].label + "'");
    pool.push_back({(*src)[i].camera, (*src)[i].label, {}, i});
  }
  if (pool.empty())
    throw Error("given mode: no candidate views (no view without image or marked unused, and "
                "no --candidates-from scene)");
  return pool;
}

// What every pick of suggest_views shares, built once inside its arena.
struct PlannerContext {
  const TriangleMesh& mesh;
  const SuggestOptions& o;
  const RayCaster& caster;
  const SafetyChecker& safety;
  PinholeCamera intrinsics;  // of the sampled poses
  Vec3 up;
};

// Poses sampled around the region, the spiral turned by the pick; the
// counts go into `result`.
std::vector<Scored> sampled_candidates(const PlannerContext& ctx, const WorstRegion& region,
                                       double viewing_distance, int pick, SuggestResult* result) {
  SamplingOptions so = ctx.o.sampling;
  so.seed = ctx.o.sampling.seed + std::uint64_t(pick);
  const CandidateSet set = sample_candidates(region, ctx.intrinsics, ctx.up, viewing_distance, ctx.safety, so);
  result->candidates_generated += set.generated;
  result->rejected_inside += set.rejected_inside;
  result->rejected_too_close += set.rejected_too_close;
  result->rejected_below_ground += set.rejected_below_ground;
  std::vector<Scored> candidates;
  for (const auto& c : set.cameras) candidates.push_back({c, candidate_mode_name(CandidateMode::Sampled), {}});
  if (candidates.empty())
    throw Error("no candidate left: all " + std::to_string(result->candidates_generated) +
                " sampled poses were inside the mesh, nearer than the safety distance (" +
                std::to_string(ctx.safety.distance()) + ") to it" +
                (ctx.o.above_ground ? std::string(" or below the ground") : std::string()));
  return candidates;
}

// Refined mode: the best scored poses improved by the optimiser, ranked
// with the others; the energy evaluations are added to `evaluated`.
void add_refined(const PlannerContext& ctx, const EnergyEvaluator& energy, const GainEvaluator* gain,
                 std::vector<Scored>* scored, std::size_t* evaluated) {
  const std::size_t n = std::min<std::size_t>(std::size_t(ctx.o.refine_best), scored->size());
  std::vector<Scored> refined(n);
  std::vector<std::size_t> evaluations(n, 0);
  auto evaluate = [&](const PinholeCamera& c) { return gain ? gain->evaluate(c) : energy.evaluate(c); };
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    refined[i] = (*scored)[i];
    refined[i].camera = refine_candidate(
        (*scored)[i].camera, ctx.up, [&](const PinholeCamera& c) { return evaluate(c).total; },
        energy.region().centroid, ctx.safety, ctx.o.refine, &evaluations[i]);
    refined[i].energy = evaluate(refined[i].camera);
    refined[i].label = candidate_mode_name(CandidateMode::Refined);
  });
  // The energy evaluations made: the optimiser's, plus the final pose's
  // evaluation of each refined candidate.
  for (std::size_t k : evaluations) *evaluated += k + 1;
  scored->insert(scored->begin(), refined.begin(), refined.end());
  std::stable_sort(scored->begin(), scored->end(), ranked_before);
}

Suggestion suggestion_of(const PlannerContext& ctx, const Scored& best, int pick, int region_index,
                         const WorstRegion& region, const EnergyEvaluator& energy) {
  Suggestion s;
  s.rank = pick + 1;
  s.label = "nbv_" + std::to_string(pick + 1);
  s.source = best.label;
  s.region = region_index;
  s.camera = best.camera;
  s.look_at = look_at_point(best.camera, ctx.caster, region.centroid);
  s.energy = best.energy;
  s.seen_faces = energy.seen_faces(best.camera);
  return s;
}

// Marks the region's faces done and moves to the worst region of the
// others; false when every observed face has been covered.
bool next_region(const PlannerContext& ctx, const std::vector<float>& pri, std::vector<char>* done,
                 WorstRegion* region) {
  for (int f : region->faces) (*done)[std::size_t(f)] = 1;
  try {
    *region = worst_region(ctx.mesh, pri, ctx.o.worst_k, done);
  } catch (const Error&) {
    return false;
  }
  return true;
}

}  // namespace

SuggestResult suggest_views(const Scene& scene, const std::vector<float>& pri,
                            const SuggestOptions& o, const std::vector<View>& given,
                            const ProgressCallback& progress, const CandidateScorer& scorer) {
  o.check();
  const auto start = std::chrono::steady_clock::now();
  const TriangleMesh& mesh = scene.mesh;
  mesh.validate(scene.mesh_path);
  if (mesh.empty()) throw Error("the mesh has no faces");
  const std::vector<PinholeCamera> existing_cams = existing_cameras(scene);
  std::vector<Scored> pool;  // given candidates
  if (o.mode == CandidateMode::Given) pool = given_pool(scene, given);

  const int threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  SuggestResult result;
  arena.execute([&] {
    const RayCaster caster(mesh);
    const double diag = mesh.bounding_box().diagonal();
    SafetyChecker safety(mesh, caster, o.safety_distance * diag);
    const Vec3 level = level_up(existing_cams);
    if (o.above_ground && o.mode != CandidateMode::Given) {
      // The ground: the mesh's lowest point plus the safety distance, or
      // the lowest existing camera where one is lower (views from below a
      // ceiling or an overhang stay possible).
      double ground = ground_height(mesh, level) + safety.distance();
      for (const auto& c : existing_cams) ground = std::min(ground, level.dot(c.center()));
      safety.set_ground(level, ground);
    }
    const PlannerContext ctx{mesh, o, caster, safety, most_common_intrinsics(existing_cams),
                             o.level_views ? level : mean_up(existing_cams)};
    std::vector<Vec3> existing;
    for (const auto& c : existing_cams) existing.push_back(c.center());

    // The whole-mesh energy: one evaluator for the batch, each pick added to
    // it; its region (what sampled candidates look at) is the K faces of
    // largest weighted deficit, chosen again after every pick.
    std::unique_ptr<GainEvaluator> gain;
    if (o.energy_kind == EnergyKind::Reconstructability)
    {
      GainOptions go = o.gain;
      go.visibility = o.energy.visibility;
      gain = std::make_unique<GainEvaluator>(mesh, caster, pri, existing_cams, go);
    }
    std::vector<char> done(mesh.num_faces(), 0);
    WorstRegion region = gain ? worst_region(mesh, gain->face_deficits(), o.worst_k) : worst_region(mesh, pri, o.worst_k);
    result.regions.push_back(region);
    std::set<int> region_seen;
    const double viewing_distance = median_viewing_distance(existing_cams, caster, region.centroid);

    for (int pick = 0; pick < o.top; ++pick) {
      const EnergyEvaluator energy(mesh, caster, region, existing, o.energy);
      std::vector<Scored> scored =
          o.mode == CandidateMode::Given
              ? score(pool, energy, gain.get(), mesh, o.energy, scorer)
              : score(sampled_candidates(ctx, region, viewing_distance, pick, &result), energy, gain.get(), mesh,
                      o.energy, scorer);
      result.candidates_evaluated += scored.size();
      if (o.mode == CandidateMode::Refined)
        add_refined(ctx, energy, gain.get(), &scored, &result.candidates_evaluated);
      if (pick == 0) {
        const std::size_t keep = o.mode == CandidateMode::Given ? scored.size() : std::min<std::size_t>(50, scored.size());
        for (std::size_t i = 0; i < keep; ++i)
          result.ranking.push_back({scored[i].label, scored[i].camera, scored[i].energy});
      }
      const Scored& best = scored.front();
      result.suggestions.push_back(
          suggestion_of(ctx, best, pick, int(result.regions.size()) - 1, region, energy));
      if (gain) result.suggestions.back().improved_faces = gain->improved_faces(best.camera, 100);
      const Suggestion& s = result.suggestions.back();
      report_progress(progress, double(pick + 1) / o.top, "suggest");

      // The pick now exists: parallax for later picks, out of the given pool.
      existing.push_back(best.camera.center());
      if (best.given_index != std::size_t(-1))
        pool.erase(std::remove_if(pool.begin(), pool.end(),
                                  [&](const Scored& c) { return c.given_index == best.given_index; }),
                   pool.end());
      if (pick + 1 == o.top) break;
      if (o.mode == CandidateMode::Given && pool.empty()) break;
      if (gain) {
        gain->add_view(best.camera);
        const WorstRegion next = worst_region(mesh, gain->face_deficits(), o.worst_k);
        if (next.faces != region.faces) {
          region = next;
          result.regions.push_back(region);
        }
        continue;
      }
      region_seen.insert(s.seen_faces.begin(), s.seen_faces.end());
      if (region_seen.size() == region.faces.size()) {
        if (!next_region(ctx, pri, &done, &region)) break;
        result.regions.push_back(region);
        region_seen.clear();
      }
    }
  });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace meshnbv
