#pragma once
// Random-access bytes for the reader: a file (pread) or a buffer in memory.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace uavmot::mcap::detail {

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual uint64_t size() const = 0;
  // Reads exactly `size` bytes at `offset` into `out` (resized). Throws InputError on I/O failure;
  // the caller checks the range against size() first.
  virtual void read(uint64_t offset, uint64_t size, std::vector<uint8_t>& out) = 0;
};

// Throws InputError naming `path` if it cannot be opened or is not a regular file.
std::unique_ptr<ByteSource> open_file_source(const std::string& path);
std::unique_ptr<ByteSource> memory_source(std::vector<uint8_t> bytes);

}  // namespace uavmot::mcap::detail
