// Fuzz target for the MCAP reader: any bytes must give either a clean InputError or a
// readable file; never a crash, a hang, an unbounded allocation or another exception type.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_targets.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/mcap/reader.hpp"

namespace uavmot::fuzz {

int mcap_reader(const uint8_t* data, size_t size) {
  using namespace uavmot::mcap;
  ReaderOptions options;
  options.max_record_bytes = 64ull << 20;  // keep within libFuzzer's memory limit
  Reader reader(options);
  try {
    reader.open_memory(std::vector<uint8_t>(data, data + size), "fuzz.mcap");
  } catch (const uavmot::InputError&) {
    return 0;
  }
  (void)reader.chunks();
  uint64_t checksum = reader.statistics().message_count;

  // Skip mode reads everything readable; Throw mode stops at the first damage.
  for (OnDamage mode : {OnDamage::Skip, OnDamage::Throw}) {
    ReadFilter filter;
    filter.on_damage = mode;
    try {
      MessageCursor cursor = reader.messages(filter);
      MessageView m;
      while (cursor.next(m)) {
        checksum += m.log_time + m.channel->id + m.size;
        if (m.size > 0) checksum += m.data[0] + m.data[m.size - 1];  // touch both ends under ASan
      }
    } catch (const uavmot::InputError&) {
    }
  }
  volatile uint64_t sink = checksum;  // keep the reads from being optimised away
  (void)sink;
  return 0;
}

}  // namespace uavmot::fuzz
