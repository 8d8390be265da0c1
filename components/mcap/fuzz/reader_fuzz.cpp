// libFuzzer target for the MCAP reader: any bytes must give either a clean InputError or a
// readable file; never a crash, a hang, an unbounded allocation or another exception type.
//
// Build with clang: cmake -DCMAKE_CXX_COMPILER=clang++ -DUAVMOT_FUZZ=ON ... && ninja mcap_reader_fuzz
// Run: build/tests/mcap_reader_fuzz -max_total_time=60 components/mcap/fuzz/corpus

#include <cstddef>
#include <cstdint>
#include <vector>

#include "uavmot/core/error.hpp"
#include "uavmot/mcap/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
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
  return checksum == 0xdeadbeef ? 1 : 0;  // keep the reads from being optimised away
}
