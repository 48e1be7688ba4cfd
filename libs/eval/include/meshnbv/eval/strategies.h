// How the incremental loop chooses the next view, besides the next-best-view
// energy (planner.h): the baselines of the paper's experiment.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "meshnbv/camera.h"
#include "meshnbv/mesh.h"

namespace meshnbv::eval {

enum class Strategy { Nbv, Uniform, Random, Coverage };
Strategy parse_strategy(const std::string& name);  // nbv | uniform | random | coverage
std::string strategy_name(Strategy strategy);

// The point nearest (least squares) to all optical axes: what a ring or
// a hemisphere of cameras looks at. The mean centre if the axes are parallel.
Vec3 convergence_point(const std::vector<PinholeCamera>& cameras);

// Uniform spacing, incrementally: the candidate whose direction from
// `centre` makes the largest angle with its nearest selected view
// (farthest-point order on the viewing sphere). Ties: the lowest index.
// -1 when there is no candidate.
int pick_uniform(const std::vector<PinholeCamera>& selected,
                 const std::vector<PinholeCamera>& candidates, const Vec3& centre);

// Best coverage: the candidate seeing the most faces of `mesh` that fewer
// than `min_views` selected views see (SPEC section 2 visibility, as PRI).
// Ties: the lowest index. -1 when there is no candidate; 0 when nothing is
// left to cover is not special (the lowest index with the most, possibly 0).
int pick_coverage(const TriangleMesh& mesh, const std::vector<PinholeCamera>& selected,
                  const std::vector<PinholeCamera>& candidates, int min_views = 2,
                  std::vector<int>* counts = nullptr);

// A uniformly random candidate index in [0, count).
int pick_random(std::size_t count, std::mt19937_64& rng);

}  // namespace meshnbv::eval
