#include "assignment.hpp"

#include <algorithm>
#include <limits>

namespace uavmot::eval::detail {

std::vector<std::pair<int, int>> maximize_assignment(const std::vector<std::vector<double>>& score) {
  const int rows = static_cast<int>(score.size());
  const int cols = rows > 0 ? static_cast<int>(score[0].size()) : 0;
  if (rows == 0 || cols == 0) return {};
  const bool transpose = rows > cols;  // the algorithm below needs n <= m
  const int n = transpose ? cols : rows, m = transpose ? rows : cols;
  const auto cost = [&](int i, int j) { return transpose ? -score[j][i] : -score[i][j]; };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = cost(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<std::pair<int, int>> pairs;
  for (int j = 1; j <= m; ++j) {
    if (p[j] == 0) continue;
    if (transpose) pairs.emplace_back(j - 1, p[j] - 1);
    else pairs.emplace_back(p[j] - 1, j - 1);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace uavmot::eval::detail
