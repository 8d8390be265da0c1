#pragma once
// Which stream ids the sink writes. Stream ids come from the wire and name the result folders
// (out/<stream>/) and preview files, so a sample is written only when its id is a safe path
// component (uavmot/core/stream_id.hpp) and belongs to the run: the first valid ids that arrive
// bind the run, up to --streams of them (or exactly the ids of --stream-id), and no other id may
// open, truncate or end anything. An end-of-stream only ends the bound stream it names.
// Every refused sample is counted and logged (the first of each id, then every 100th).

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace uavmot::sink {

class StreamGate {
 public:
  // MAX_STREAMS ids may bind; with EXPECTED (not empty) only those ids.
  explicit StreamGate(int max_streams, std::vector<std::string> expected = {});

  enum class Verdict { Bound, Unbound, Refused };
  // Where ID stands, without binding: Unbound is a valid id there is room for. Refused is counted
  // and logged.
  Verdict check(const std::string& topic, const std::string& id);
  // A result sample of ID on TOPIC: true when ID is bound, or is now bound (logged). A refused
  // sample is counted and logged. Call after the sample itself was validated, so a malformed
  // sample never binds.
  bool admit(const std::string& topic, const std::string& id);
  // Whether ADMIT would accept ID, without binding or counting (validate before binding).
  bool would_admit(const std::string& id) const { return refusal(id).empty(); }
  // Counts and logs a sample of ID as refused for WHY.
  void refuse(const std::string& topic, const std::string& id, const std::string& why);
  // An end-of-stream of ID on TOPIC: true only when ID is bound; otherwise counted and logged.
  bool admit_end(const std::string& topic, const std::string& id);

  bool is_bound(const std::string& id) const { return bound_.count(id) > 0; }
  const std::set<std::string>& bound() const { return bound_; }
  uint64_t refused() const { return refused_; }
  // One log line per refused id (at most the first 32 ids; the rest are summed).
  void log_summary() const;

 private:
  std::string refusal(const std::string& id) const;

  size_t max_streams_;
  std::set<std::string> expected_;
  std::set<std::string> bound_;
  uint64_t refused_ = 0;
  std::map<std::string, std::pair<std::string, uint64_t>> refused_ids_;  // printable id -> why, count
  uint64_t refused_other_ids_ = 0;  // beyond the ids kept
};

}  // namespace uavmot::sink
