#pragma once
// A number exactly as the result files print it with fixed decimals (fmt "{:.Nf}"), held as an
// integer: the printed digits without the point, and -1 - digits when it is printed with a minus
// sign (so "-0.000" survives). Printing it back gives the same text, so whoever holds these
// integers writes the same bytes as whoever held the double (the downlink's regions).

#include <cstdint>
#include <string>

namespace uavmot {

// Throws InvalidArgument when `value` is not finite or its digits exceed int64.
int64_t printed_fixed(double value, int decimals);
// The text fmt::format("{:.Nf}", value) gave for printed_fixed(value, N).
std::string format_printed_fixed(int64_t printed, int decimals);

}  // namespace uavmot
