// Tour order: nearest neighbour, then 2-opt (plan.h).
#include <algorithm>
#include <limits>

#include "meshnbv/mission/plan.h"

namespace meshnbv::mission {

double tour_length(const Vec3& start, const std::vector<Vec3>& p, const std::vector<int>& order) {
  double len = 0;
  Vec3 at = start;
  for (int i : order) {
    len += (p[std::size_t(i)] - at).norm();
    at = p[std::size_t(i)];
  }
  return len + (start - at).norm();
}

std::vector<int> nearest_neighbour_order(const Vec3& start, const std::vector<Vec3>& p) {
  std::vector<int> order;
  std::vector<char> used(p.size(), 0);
  Vec3 at = start;
  for (std::size_t k = 0; k < p.size(); ++k) {
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (!used[i] && (p[i] - at).squaredNorm() < best_d) {
        best_d = (p[i] - at).squaredNorm();
        best = int(i);
      }
    used[std::size_t(best)] = 1;
    order.push_back(best);
    at = p[std::size_t(best)];
  }
  return order;
}

std::vector<int> two_opt(const Vec3& start, const std::vector<Vec3>& p, std::vector<int> order) {
  // Positions along the tour: 0 = start, 1..n = order, n+1 = start again.
  const std::size_t n = order.size();
  auto at = [&](std::size_t k) -> const Vec3& {
    return k == 0 || k == n + 1 ? start : p[std::size_t(order[k - 1])];
  };
  for (bool improved = true; improved;) {
    improved = false;
    for (std::size_t i = 0; i + 1 < n + 1; ++i)
      for (std::size_t j = i + 2; j <= n; ++j) {
        // Edges (i, i+1) and (j, j+1) -> (i, j) and (i+1, j+1): reverse i+1..j.
        const double before = (at(i + 1) - at(i)).norm() + (at(j + 1) - at(j)).norm();
        const double after = (at(j) - at(i)).norm() + (at(j + 1) - at(i + 1)).norm();
        if (after < before - 1e-12 * (1 + before)) {
          std::reverse(order.begin() + long(i), order.begin() + long(j));
          improved = true;
        }
      }
  }
  return order;
}

std::vector<int> route_order(const Vec3& start, const std::vector<Vec3>& points) {
  return two_opt(start, points, nearest_neighbour_order(start, points));
}

}  // namespace meshnbv::mission
