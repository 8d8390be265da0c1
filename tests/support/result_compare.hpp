#pragma once
// Compares two result files (MOTChallenge text / CSV) written by ResultFilesWriter: same lines,
// same fields, same text; numbers may differ by at most one unit of their last printed digit.
// That is what the compact downlink's float32 boxes can change (docs/deployment.md); anything
// more is a real difference.

#include <string>

namespace uavmot::testing {

struct CompareResult {
  std::string difference;  // empty: equal within one unit of the last printed digit
  int numbers_differing = 0;
  bool equal() const { return difference.empty(); }
};

CompareResult compare_to_last_digit(const std::string& file_a, const std::string& file_b);

}  // namespace uavmot::testing
