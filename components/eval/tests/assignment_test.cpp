#include <gtest/gtest.h>

#include "../src/assignment.hpp"

namespace uavmot::eval::detail {
namespace {

double total(const std::vector<std::vector<double>>& s, const std::vector<std::pair<int, int>>& pairs) {
  double sum = 0;
  for (const auto& [r, c] : pairs) sum += s[r][c];
  return sum;
}

TEST(Assignment, FindsTheMaximumOfASquareProblem) {
  // Greedy would take 9 and then 1 (10); the optimum is 8 + 7 = 15.
  const std::vector<std::vector<double>> s{{9, 8}, {7, 1}};
  const auto pairs = maximize_assignment(s);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_DOUBLE_EQ(total(s, pairs), 15.0);
  EXPECT_EQ(pairs[0], std::make_pair(0, 1));
  EXPECT_EQ(pairs[1], std::make_pair(1, 0));
}

TEST(Assignment, RectangularBothWays) {
  const std::vector<std::vector<double>> wide{{1, 5, 2}, {4, 6, 1}};
  auto pairs = maximize_assignment(wide);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_DOUBLE_EQ(total(wide, pairs), 9.0);  // 0->1 (5) + 1->0 (4)
  const std::vector<std::vector<double>> tall{{1, 4}, {5, 6}, {2, 1}};
  pairs = maximize_assignment(tall);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_DOUBLE_EQ(total(tall, pairs), 9.0);  // 0->1 (4) + 1->0 (5)
  EXPECT_TRUE(maximize_assignment({}).empty());
}

}  // namespace
}  // namespace uavmot::eval::detail
