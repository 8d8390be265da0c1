#include "result_compare.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "child_process.hpp"

namespace uavmot::testing {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, separator)) out.push_back(item);
  return out;
}

int decimals(const std::string& number) {
  const auto dot = number.find('.');
  return dot == std::string::npos ? 0 : static_cast<int>(number.size() - dot - 1);
}

bool parse(const std::string& text, double& value) {
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

}  // namespace

CompareResult compare_to_last_digit(const std::string& file_a, const std::string& file_b) {
  CompareResult result;
  const auto lines_a = split(read_file(file_a), '\n');
  const auto lines_b = split(read_file(file_b), '\n');
  if (lines_a.size() != lines_b.size()) {
    result.difference = std::to_string(lines_a.size()) + " lines vs " + std::to_string(lines_b.size());
    return result;
  }
  for (size_t i = 0; i < lines_a.size(); ++i) {
    const auto fields_a = split(lines_a[i], ','), fields_b = split(lines_b[i], ',');
    const std::string where = "line " + std::to_string(i + 1) + ": '" + lines_a[i] + "' vs '" + lines_b[i] + "'";
    if (fields_a.size() != fields_b.size()) {
      result.difference = where;
      return result;
    }
    for (size_t f = 0; f < fields_a.size(); ++f) {
      if (fields_a[f] == fields_b[f]) continue;
      double a = 0.0, b = 0.0;
      const int digits = std::max(decimals(fields_a[f]), decimals(fields_b[f]));
      // One unit of the last digit, with room for the decimal rounding of that unit itself.
      if (!parse(fields_a[f], a) || !parse(fields_b[f], b) || std::abs(a - b) > 1.001 * std::pow(10.0, -digits)) {
        result.difference = where;
        return result;
      }
      ++result.numbers_differing;
    }
  }
  return result;
}

}  // namespace uavmot::testing
