#include "meshnbv/eval/ranking.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "meshnbv/error.h"

namespace meshnbv::eval {

std::vector<double> average_ranks(const std::vector<double>& v) {
  std::vector<std::size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < idx.size();) {
    std::size_t j = i;
    while (j + 1 < idx.size() && v[idx[j + 1]] == v[idx[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[idx[k]] = 0.5 * double(i + j) + 1.0;
    i = j + 1;
  }
  return r;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw Error("spearman: the two lists differ in length");
  if (a.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  const auto ra = average_ranks(a), rb = average_ranks(b);
  const double n = double(ra.size());
  const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / n;
  const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - ma) * (rb[i] - mb);
    saa += (ra[i] - ma) * (ra[i] - ma);
    sbb += (rb[i] - mb) * (rb[i] - mb);
  }
  if (!(saa > 0 && sbb > 0)) return std::numeric_limits<double>::quiet_NaN();
  return sab / std::sqrt(saa * sbb);
}

double roc_auc(const std::vector<double>& score, const std::vector<bool>& positive) {
  if (score.size() != positive.size()) throw Error("roc_auc: scores and labels differ in length");
  const auto r = average_ranks(score);
  double sum_pos = 0, n_pos = 0, n_neg = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (positive[i]) {
      sum_pos += r[i];
      ++n_pos;
    } else {
      ++n_neg;
    }
  }
  if (n_pos == 0 || n_neg == 0) return std::numeric_limits<double>::quiet_NaN();
  return (sum_pos - n_pos * (n_pos + 1) / 2) / (n_pos * n_neg);
}

}  // namespace meshnbv::eval
