#include "uavmot/core/stream_id.hpp"

#include <fmt/format.h>

namespace uavmot {
namespace {
bool allowed(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
}
}  // namespace

std::string stream_id_problem(std::string_view id) {
  if (id.empty()) return "empty stream id";
  if (id.size() > kMaxStreamIdLength) return fmt::format("stream id longer than {} characters", kMaxStreamIdLength);
  if (id == "." || id == "..") return "stream id '.' or '..'";
  for (char c : id) {
    if (!allowed(c)) return "stream id with a character other than A-Z a-z 0-9 . _ -";
  }
  return {};
}

std::string printable_stream_id(std::string_view id) {
  constexpr size_t kShown = 80;
  std::string out = "'";
  for (size_t i = 0; i < id.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(id[i]);
    out += c >= 0x20 && c < 0x7f && c != '\'' && c != '\\' ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
  }
  out += "'";
  if (id.size() > kShown) out += fmt::format(" ({} characters)", id.size());
  return out;
}

}  // namespace uavmot
