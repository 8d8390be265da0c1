#pragma once
// Chunk compression: zstd frames and LZ4 frames, as the MCAP spec requires.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "uavmot/mcap/types.hpp"

namespace uavmot::mcap::detail {

// Holds the codec contexts so repeated chunks reuse them.
class Codec {
 public:
  Codec();
  ~Codec();
  Codec(const Codec&) = delete;
  Codec& operator=(const Codec&) = delete;

  // Replaces `out` with the compressed bytes. `level` 0 picks a fast default per codec.
  // `threads` > 0 lets zstd compress one chunk on that many worker threads.
  void compress(Compression compression, int level, int threads, const uint8_t* data, size_t size,
                std::vector<uint8_t>& out);

  // Decompresses exactly `out_size` bytes named by the spec string ("", "lz4", "zstd") into
  // `out`. Throws std::runtime_error with the reason on any mismatch or unknown compression.
  void decompress(std::string_view compression, const uint8_t* data, size_t size, uint8_t* out, size_t out_size);

 private:
  struct Contexts;
  std::unique_ptr<Contexts> contexts_;
};

}  // namespace uavmot::mcap::detail
