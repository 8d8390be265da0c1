#include "uavmot/core/printed_number.hpp"

#include <cmath>

#include <fmt/format.h>

#include "uavmot/core/error.hpp"

namespace uavmot {

int64_t printed_fixed(double value, int decimals) {
  // 9e18 fits int64 with room; fmt's text is then at most 19 digits.
  if (!std::isfinite(value) || decimals < 0 || decimals > 9 || std::abs(value) * std::pow(10.0, decimals) >= 9e18) {
    throw InvalidArgument(fmt::format("{} cannot be held with {} decimals", value, decimals));
  }
  const std::string text = fmt::format("{:.{}f}", value, decimals);
  const bool negative = text.front() == '-';
  int64_t digits = 0;
  for (char c : text) {
    if (c >= '0' && c <= '9') digits = digits * 10 + (c - '0');
  }
  return negative ? -1 - digits : digits;
}

std::string format_printed_fixed(int64_t printed, int decimals) {
  const bool negative = printed < 0;
  std::string digits = std::to_string(negative ? -(printed + 1) : printed);
  if (digits.size() < static_cast<size_t>(decimals) + 1) digits.insert(0, decimals + 1 - digits.size(), '0');
  if (decimals > 0) digits.insert(digits.size() - decimals, ".");
  return negative ? "-" + digits : digits;
}

}  // namespace uavmot
