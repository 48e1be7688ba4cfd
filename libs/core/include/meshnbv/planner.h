// Suggest Next View: scores candidate poses with the energy of energy.h over
// the worst region and returns the best ones, greedily in batches.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "meshnbv/candidates.h"
#include "meshnbv/gain.h"
#include "meshnbv/progress.h"
#include "meshnbv/scene.h"

namespace meshnbv {

enum class CandidateMode { Given, Sampled, Refined };
CandidateMode parse_candidate_mode(const std::string& name);  // given | sampled | refined
std::string candidate_mode_name(CandidateMode mode);

struct SuggestOptions {
  int worst_k = 10;          // faces in the worst set
  int top = 3;               // suggestions to return (greedy batch)
  CandidateMode mode = CandidateMode::Sampled;
  // paper: the SPEC's energy over the worst region (`energy`); reconstructability:
  // the whole-mesh gain (`gain`, gain.h).
  EnergyKind energy_kind = EnergyKind::Paper;
  EnergyOptions energy;
  GainOptions gain;
  SamplingOptions sampling;
  double safety_distance = 0.05;  // share of the bounding-box diagonal
  // sampled, refined: no pose below the ground: the mesh's lowest point
  // (ground_height along level_up of the existing views) plus the safety
  // distance, or the lowest existing view where that is lower. On by
  // default (beyond the SPEC's hemisphere; docs/deviations.md).
  bool above_ground = true;
  // sampled, refined: poses without roll, their image up in the plane of
  // level_up (the existing views' right axes are level) and the view
  // direction, as a gimbal takes them; off = the SPEC's mean image up.
  // On by default (docs/deviations.md).
  bool level_views = true;
  int refine_best = 8;            // refined mode: sampled candidates refined per pick
  RefineOptions refine;
  int threads = 0;                // 0 = all cores

  void check() const;
};

struct Suggestion {
  int rank = 0;                 // 1 = best
  std::string label;            // nbv_1, nbv_2, ...
  std::string source;           // the candidate's own label (given) or sampled / refined
  int region = 0;               // index into SuggestResult::regions
  PinholeCamera camera;
  Vec3 look_at = Vec3::Zero();
  EnergyTerms energy;
  std::vector<int> seen_faces;  // worst faces of its region that it sees
  // reconstructability: the faces it improves most, best first (at most 100).
  std::vector<int> improved_faces;
};

struct RankedCandidate {
  std::string label;
  PinholeCamera camera;
  EnergyTerms energy;
};

struct SuggestResult {
  std::vector<Suggestion> suggestions;
  std::vector<WorstRegion> regions;
  // Every candidate scored for the first pick, best first (all of them in
  // given mode; the best 50 otherwise).
  std::vector<RankedCandidate> ranking;
  std::size_t candidates_generated = 0, candidates_evaluated = 0;
  std::size_t rejected_inside = 0, rejected_too_close = 0, rejected_below_ground = 0;
  double seconds = 0;
};

// `pri` per face of scene.mesh (NaN = unobserved). Existing views: those
// with an image and used. Given candidates: `given` when non-empty, else
// the scene's views without image or marked unused.
//
// Batches: each pick is added to the existing views (it counts for the
// parallax of later picks and is removed from the given candidates); once
// the picks made for a region together see all of its worst faces, those
// faces are set aside and the next K worst faces form the next region.
// How suggest_views scores a set of candidate poses with one evaluator:
// must return energy.evaluate(c) for each candidate, in order. Empty = in
// parallel on this process; meshnbv-mpi spreads the candidates over its
// ranks (docs/scale.md). `options` are the evaluator's energy options.
using CandidateScorer = std::function<std::vector<EnergyTerms>(
    const TriangleMesh& mesh, const EnergyEvaluator& energy, const EnergyOptions& options,
    const std::vector<PinholeCamera>& candidates)>;

SuggestResult suggest_views(const Scene& scene, const std::vector<float>& pri,
                            const SuggestOptions& options, const std::vector<View>& given = {},
                            const ProgressCallback& progress = {}, const CandidateScorer& scorer = {});

}  // namespace meshnbv
