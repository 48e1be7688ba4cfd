// Repeated loops from starting sets spread over the dataset, and their
// summary per view count (mean, Student t interval).
#include "meshnbv/eval/experiment.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <boost/math/distributions/students_t.hpp>
#include <nlohmann/json.hpp>

#include "meshnbv/error.h"
#include "meshnbv/eval/strategies.h"
#include "meshnbv/io/file_util.h"

namespace fs = std::filesystem;

namespace meshnbv::eval {
namespace {

// View `centre` and the size-1 views whose camera centres are nearest to
// its centre (ties: the lower index), sorted.
std::vector<int> around(const std::vector<View>& views, int centre, int size) {
  std::vector<std::pair<double, int>> by_distance;
  const Vec3 c0 = views[std::size_t(centre)].camera.center();
  for (std::size_t i = 0; i < views.size(); ++i)
    if (int(i) != centre) by_distance.emplace_back((views[i].camera.center() - c0).norm(), int(i));
  std::stable_sort(by_distance.begin(), by_distance.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<int> out{centre};
  for (int k = 0; k + 1 < size; ++k) out.push_back(by_distance[std::size_t(k)].second);
  std::sort(out.begin(), out.end());
  return out;
}

nlohmann::json interval_json(const MeanInterval& m) {
  auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"runs", m.n}, {"mean", num(m.mean)}, {"ci_low", num(m.low)}, {"ci_high", num(m.high)},
          {"min", num(m.min)}, {"max", num(m.max)}};
}

}  // namespace

std::vector<std::vector<int>> spread_bootstraps(const std::vector<View>& views, int count, int size) {
  const int n = int(views.size());
  if (count < 1 || count > n)
    throw Error("bootstraps: " + std::to_string(count) + " starting sets asked of " + std::to_string(n) +
                " views (each needs its own centre view)");
  if (size < 1 || size > n)
    throw Error("bootstraps: a starting set of " + std::to_string(size) + " views asked of " +
                std::to_string(n) + " views");
  std::vector<PinholeCamera> cams;
  for (const View& v : views) cams.push_back(v.camera);
  const Vec3 centre = convergence_point(cams);
  std::vector<int> centres{0};
  std::vector<PinholeCamera> chosen{cams[0]};
  while (int(centres.size()) < count) {
    std::vector<int> left;
    std::vector<PinholeCamera> left_cams;
    for (int i = 0; i < n; ++i)
      if (std::find(centres.begin(), centres.end(), i) == centres.end()) {
        left.push_back(i);
        left_cams.push_back(cams[std::size_t(i)]);
      }
    const int pick = pick_uniform(chosen, left_cams, centre);
    centres.push_back(left[std::size_t(pick)]);
    chosen.push_back(cams[std::size_t(centres.back())]);
  }
  std::vector<std::vector<int>> out;
  for (int c : centres) out.push_back(around(views, c, size));
  return out;
}

double student_t_critical(int dof, double level) {
  check_option(dof >= 1, "t critical value degrees of freedom", ">= 1", dof);
  check_option(level > 0 && level < 1, "confidence level", "in (0, 1)", level);
  const boost::math::students_t t(dof);
  return boost::math::quantile(t, 0.5 + 0.5 * level);
}

MeanInterval mean_interval(const std::vector<double>& values, double level) {
  MeanInterval m;
  std::vector<double> x;
  for (double v : values)
    if (std::isfinite(v)) x.push_back(v);
  m.n = x.size();
  if (x.empty()) return m;
  double sum = 0;
  for (double v : x) sum += v;
  m.mean = sum / double(x.size());
  m.min = *std::min_element(x.begin(), x.end());
  m.max = *std::max_element(x.begin(), x.end());
  m.low = m.high = m.mean;
  if (x.size() >= 2) {
    double ss = 0;
    for (double v : x) ss += (v - m.mean) * (v - m.mean);
    const double sd = std::sqrt(ss / double(x.size() - 1));
    const double half = student_t_critical(int(x.size()) - 1, level) * sd / std::sqrt(double(x.size()));
    m.low = m.mean - half;
    m.high = m.mean + half;
  }
  return m;
}

std::vector<RunsRow> summarize_runs(const std::vector<LoopResult>& runs, double level) {
  // (num_views, metric) -> values over the runs; metrics in steps.csv's order.
  std::map<std::size_t, std::vector<std::pair<std::string, std::vector<double>>>> table;
  auto add = [&](std::size_t views, const std::string& metric, double value) {
    auto& metrics = table[views];
    auto it = std::find_if(metrics.begin(), metrics.end(), [&](const auto& e) { return e.first == metric; });
    if (it == metrics.end()) it = metrics.insert(metrics.end(), {metric, {}});
    it->second.push_back(value);
  };
  for (const LoopResult& r : runs)
    for (const StepRecord& s : r.steps) {
      const std::size_t views = s.views.size();
      for (const auto& [p, v] : s.metrics.accuracy) add(views, "accuracy_" + csv_label(p), v);
      for (const auto& [t, v] : s.metrics.completeness) add(views, "completeness_" + csv_label(t), v);
      add(views, "mean_accuracy", s.metrics.mean_accuracy);
      add(views, "faces", double(s.faces));
    }
  std::vector<RunsRow> rows;
  for (const auto& [views, metrics] : table)
    for (const auto& [metric, values] : metrics) rows.push_back({views, metric, mean_interval(values, level)});
  return rows;
}

std::vector<std::pair<std::string, MeanInterval>> summarize_curve_areas(const std::vector<LoopResult>& runs,
                                                                        double level) {
  std::vector<std::pair<std::string, std::vector<double>>> areas;
  for (const LoopResult& r : runs) {
    if (r.steps.empty()) continue;
    const auto& thresholds = r.steps[0].metrics.completeness;
    for (std::size_t k = 0; k < thresholds.size(); ++k) {
      double sum = 0;
      for (const StepRecord& s : r.steps) sum += k < s.metrics.completeness.size() ? s.metrics.completeness[k].second : 0.0;
      const std::string name = "completeness_" + csv_label(thresholds[k].first);
      auto it = std::find_if(areas.begin(), areas.end(), [&](const auto& e) { return e.first == name; });
      if (it == areas.end()) it = areas.insert(areas.end(), {name, {}});
      it->second.push_back(sum / double(r.steps.size()));
    }
  }
  std::vector<std::pair<std::string, MeanInterval>> out;
  for (const auto& [name, values] : areas) out.emplace_back(name, mean_interval(values, level));
  return out;
}

std::string runs_csv(const std::vector<RunsRow>& rows) {
  std::ostringstream ss;
  ss << "num_views,metric,runs,mean,ci_low,ci_high,min,max\n";
  for (const RunsRow& r : rows)
    ss << r.num_views << "," << r.metric << "," << r.value.n << "," << csv_number(r.value.mean) << ","
       << csv_number(r.value.low) << "," << csv_number(r.value.high) << "," << csv_number(r.value.min) << ","
       << csv_number(r.value.max) << "\n";
  return ss.str();
}

std::uint64_t bootstrap_seed(std::uint64_t seed, int b) {
  if (b <= 1) return seed;
  std::uint64_t x = seed ^ (std::uint64_t(b) * 0x9E3779B97F4A7C15ull);
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  // 31 bits: the range of the seed options (options.h).
  return (x ^ (x >> 31)) >> 33;
}

BootstrapRuns run_bootstraps(const Dataset& dataset, const LoopOptions& options,
                             const std::vector<std::vector<int>>& bootstraps, const ProgressCallback& progress,
                             const std::function<void(int, const StepRecord&)>& on_step) {
  options.check();
  if (bootstraps.empty()) throw Error("bootstraps: no starting set");
  constexpr double kLevel = 0.95;
  const fs::path out(options.out_dir);
  fs::create_directories(out);
  BootstrapRuns result;
  result.bootstraps = bootstraps;
  auto write_summary = [&]() {
    nlohmann::json j;
    j["format"] = "meshnbv-loop-bootstraps";
    j["version"] = 1;
    j["dataset"] = dataset.path;
    j["strategy"] = strategy_name(options.strategy);
    j["level"] = kLevel;
    j["runs"] = nlohmann::json::array();
    for (std::size_t b = 0; b < bootstraps.size(); ++b) {
      nlohmann::json run = {{"folder", "bootstrap_" + std::to_string(b + 1)},
                            {"bootstrap_views", bootstraps[b]},
                            {"seed", bootstrap_seed(options.seed, int(b + 1))},
                            {"done", b < result.runs.size()}};
      if (b < result.runs.size()) run["seconds"] = result.runs[b].seconds;
      j["runs"].push_back(run);
    }
    j["curve_areas"] = nlohmann::json::object();
    for (const auto& [name, m] : summarize_curve_areas(result.runs, kLevel)) j["curve_areas"][name] = interval_json(m);
    // The critical values behind the intervals, by run count, for paired
    // comparisons made from these files (bench/eval/experiment.py).
    j["t_critical"] = nlohmann::json::object();
    for (std::size_t n = 2; n <= bootstraps.size(); ++n)
      j["t_critical"][std::to_string(n)] = student_t_critical(int(n) - 1, kLevel);
    io::write_atomically((out / "bootstraps.json").string(), [&](std::ostream& o) { o << j.dump(2) << "\n"; });
    io::write_atomically((out / "bootstraps.csv").string(),
                         [&](std::ostream& o) { o << runs_csv(summarize_runs(result.runs, kLevel)); });
  };
  for (std::size_t b = 0; b < bootstraps.size(); ++b) {
    LoopOptions o = options;
    o.bootstrap = int(bootstraps[b].size());
    o.bootstrap_views = bootstraps[b];
    o.seed = bootstrap_seed(options.seed, int(b + 1));
    o.suggest.sampling.seed = bootstrap_seed(options.suggest.sampling.seed, int(b + 1));
    o.out_dir = (out / ("bootstrap_" + std::to_string(b + 1))).string();
    const double share = 1.0 / double(bootstraps.size());
    ProgressCallback sub;
    if (progress)
      sub = [&, b, share](double f, const std::string& stage) {
        return progress((double(b) + f) * share, stage);
      };
    result.seeds.push_back(o.seed);
    result.runs.push_back(run_loop(dataset, o, sub, [&, b](const StepRecord& s) {
      if (on_step) on_step(int(b + 1), s);
    }));
    write_summary();
  }
  return result;
}

}  // namespace meshnbv::eval
