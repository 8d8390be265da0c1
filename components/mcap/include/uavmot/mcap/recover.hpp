#pragma once
// Repairs a recording that a crash left without its summary (FILE.mcap.tmp), or one that was
// truncated or corrupted: writes a valid, indexed file holding every message that can still
// be read (every complete chunk), in log-time order.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "uavmot/mcap/types.hpp"
#include "uavmot/mcap/writer.hpp"

namespace uavmot::mcap {

struct RecoverResult {
  uint64_t messages = 0;        // messages written to the output
  uint32_t schemas = 0;
  uint32_t channels = 0;
  std::vector<Damage> damage;   // what was lost and where; empty if the input was intact
};

// Reads `damaged_path` (by a scan when it has no usable summary) and writes `out_path` (through
// a temporary file, renamed at the end; `out_path` may equal `damaged_path`). Schemas, channels
// (with their ids) and metadata are kept. `options` default to the input's compression and
// header. Throws InputError if the input is not MCAP at all or the output cannot be written.
RecoverResult recover(const std::string& damaged_path, const std::string& out_path,
                      const std::optional<WriterOptions>& options = std::nullopt);

}  // namespace uavmot::mcap
