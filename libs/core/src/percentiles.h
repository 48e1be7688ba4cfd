// Percentiles by linear interpolation between closest ranks (numpy's
// default), from order statistics found with nth_element: the same values
// as after a full sort, in linear time.
#pragma once

#include <algorithm>
#include <initializer_list>
#include <utility>
#include <vector>

namespace meshnbv::detail {

// (percent, value) for each percent of `percents` (ascending, in [0, 100]);
// reorders `v`; empty for no values.
template <class T>
std::vector<std::pair<double, double>> interpolated_percentiles(std::vector<T>& v,
                                                                std::initializer_list<double> percents) {
  std::vector<std::pair<double, double>> out;
  if (v.empty()) return out;
  std::size_t lo = 0;  // v[0, lo) holds the lo smallest values
  for (double p : percents) {
    const double pos = p / 100.0 * double(v.size() - 1);
    const std::size_t i = std::size_t(pos);
    const double frac = pos - double(i);
    std::nth_element(v.begin() + std::ptrdiff_t(lo), v.begin() + std::ptrdiff_t(i), v.end());
    lo = i;
    if (i + 1 < v.size()) {
      const T next = *std::min_element(v.begin() + std::ptrdiff_t(i + 1), v.end());
      out.emplace_back(p, v[i] * (1 - frac) + next * frac);
    } else {
      out.emplace_back(p, v[i]);
    }
  }
  return out;
}

}  // namespace meshnbv::detail
