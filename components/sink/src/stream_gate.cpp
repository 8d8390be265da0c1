#include "uavmot/sink/stream_gate.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "uavmot/core/stream_id.hpp"

namespace uavmot::sink {
namespace {
constexpr size_t kKeptIds = 32;  // a flood of made-up ids must not grow memory
}  // namespace

StreamGate::StreamGate(int max_streams, std::vector<std::string> expected)
    : max_streams_(static_cast<size_t>(std::max(max_streams, 1))), expected_(expected.begin(), expected.end()) {}

std::string StreamGate::refusal(const std::string& id) const {
  if (bound_.count(id) > 0) return {};
  if (std::string problem = stream_id_problem(id); !problem.empty()) return problem;
  if (!expected_.empty() && expected_.count(id) == 0) return "not a stream of --stream-id";
  if (bound_.size() >= max_streams_) {
    return fmt::format("the run is bound to {} stream(s) already (--streams {})", bound_.size(), max_streams_);
  }
  return {};
}

StreamGate::Verdict StreamGate::check(const std::string& topic, const std::string& id) {
  if (bound_.count(id) > 0) return Verdict::Bound;
  if (std::string why = refusal(id); !why.empty()) {
    refuse(topic, id, why);
    return Verdict::Refused;
  }
  return Verdict::Unbound;
}

bool StreamGate::admit(const std::string& topic, const std::string& id) {
  if (bound_.count(id) > 0) return true;
  if (std::string why = refusal(id); !why.empty()) {
    refuse(topic, id, why);
    return false;
  }
  bound_.insert(id);
  spdlog::info("stream {} bound ({} of {})", printable_stream_id(id), bound_.size(), max_streams_);
  return true;
}

bool StreamGate::admit_end(const std::string& topic, const std::string& id) {
  if (bound_.count(id) > 0) return true;
  std::string why = refusal(id);
  refuse(topic, id, "end of stream of a stream that is not bound" + (why.empty() ? std::string() : ": " + why));
  return false;
}

void StreamGate::refuse(const std::string& topic, const std::string& id, const std::string& why) {
  ++refused_;
  const std::string shown = printable_stream_id(id);
  uint64_t n = 0;
  if (auto it = refused_ids_.find(shown); it != refused_ids_.end()) {
    n = ++it->second.second;
  } else if (refused_ids_.size() < kKeptIds) {
    refused_ids_.emplace(shown, std::make_pair(why, n = 1));
  } else {
    n = ++refused_other_ids_;
  }
  if (n == 1 || n % 100 == 0) spdlog::warn("{}: refused a sample of stream {} ({}x): {}", topic, shown, n, why);
}

void StreamGate::log_summary() const {
  if (refused_ == 0) return;
  spdlog::error("refused {} sample(s) of stream ids this run does not write (bound: {})", refused_,
                fmt::join(bound_, ", "));
  for (const auto& [shown, what] : refused_ids_) spdlog::error("  stream {}: {} sample(s): {}", shown, what.second, what.first);
  if (refused_other_ids_ > 0) spdlog::error("  {} sample(s) of further stream ids", refused_other_ids_);
}

}  // namespace uavmot::sink
