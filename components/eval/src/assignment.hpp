#pragma once
// Optimal assignment (Hungarian / Kuhn-Munkres), like scipy's linear_sum_assignment.

#include <utility>
#include <vector>

namespace uavmot::eval::detail {

// score[r][c]; returns min(rows, cols) (row, col) pairs maximising the total score.
std::vector<std::pair<int, int>> maximize_assignment(const std::vector<std::vector<double>>& score);

}  // namespace uavmot::eval::detail
