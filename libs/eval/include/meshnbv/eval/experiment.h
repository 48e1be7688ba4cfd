// Repeated loops (issue #15): the same strategy from several starting sets
// spread over the dataset, summarised per view count by the mean and a 95%
// confidence interval over the runs. The paired comparison of strategies
// (bench/eval/experiment.py) pairs runs by their starting set.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "meshnbv/eval/loop.h"

namespace meshnbv::eval {

// `count` starting sets of `size` views each, spread over the dataset: the
// first is view 0 and the size-1 views whose camera centres are nearest to
// its centre (the loop's default bootstrap); each next set is centred on
// the view the uniform strategy would pick next among those not yet a
// centre (the largest angle, seen from the point the cameras look at, to
// the nearest centre so far; ties: the lowest index), with its size-1
// nearest views. Each set is sorted; sets may share views, never their
// centre. Throws unless 1 <= count <= views and 1 <= size <= views.
std::vector<std::vector<int>> spread_bootstraps(const std::vector<View>& views, int count, int size);

// The two-sided Student t critical value for `dof` >= 1 degrees of freedom:
// P(|T| <= t) = level, level in (0, 1).
double student_t_critical(int dof, double level = 0.95);

// Mean of the finite values and its Student t interval at `level`
// (mean -/+ t * s / sqrt(n)); with one value the interval is that value's
// (zero width: nothing is known of the spread); with none, all NaN.
struct MeanInterval {
  std::size_t n = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
};
MeanInterval mean_interval(const std::vector<double>& values, double level = 0.95);

// One metric at one view count over the runs that reached it. Metrics:
// accuracy_<p>, completeness_<t> (as in steps.csv), mean_accuracy, faces.
struct RunsRow {
  std::size_t num_views = 0;
  std::string metric;
  MeanInterval value;
};
std::vector<RunsRow> summarize_runs(const std::vector<LoopResult>& runs, double level = 0.95);

// Per completeness threshold: the mean completeness over each run's view
// counts (the normalised area under its curve, in [0, 1]), summarised.
std::vector<std::pair<std::string, MeanInterval>> summarize_curve_areas(
    const std::vector<LoopResult>& runs, double level = 0.95);

// The rows as CSV: num_views,metric,runs,mean,ci_low,ci_high,min,max.
std::string runs_csv(const std::vector<RunsRow>& rows);

// Runs the loop once per starting set: run b (1-based) writes
// `options.out_dir`/bootstrap_<b>/ (steps.csv, loop.json, meshes/ as one
// loop) with `bootstraps[b-1]` as its bootstrap views and, for the random
// strategy, a seed derived from options.seed and b (b = 1: options.seed
// itself). Then `options.out_dir`/bootstraps.csv (summarize_runs) and
// bootstraps.json (the sets, each run's folder and seed, the curve areas
// and the t critical values by run count) are written; both are rewritten
// after every run. `on_step` sees every step with its run's index.
struct BootstrapRuns {
  std::vector<std::vector<int>> bootstraps;
  std::vector<LoopResult> runs;
  std::vector<std::uint64_t> seeds;
};
BootstrapRuns run_bootstraps(const Dataset& dataset, const LoopOptions& options,
                             const std::vector<std::vector<int>>& bootstraps,
                             const ProgressCallback& progress = {},
                             const std::function<void(int run, const StepRecord&)>& on_step = {});

// The seed of run b (1-based) of the random strategy: `seed` for b = 1,
// a SplitMix64 mix of seed and b otherwise, in [0, 2^31) as the seed
// options' range asks.
std::uint64_t bootstrap_seed(std::uint64_t seed, int b);

}  // namespace meshnbv::eval
