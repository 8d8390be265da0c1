#include "uavmot/mcap/types.hpp"

#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

std::string_view compression_name(Compression compression) {
  switch (compression) {
    case Compression::None: return "";
    case Compression::Lz4: return "lz4";
    case Compression::Zstd: return "zstd";
  }
  return "";
}

Compression parse_compression(std::string_view name) {
  if (name.empty() || name == "none") return Compression::None;
  if (name == "lz4") return Compression::Lz4;
  if (name == "zstd") return Compression::Zstd;
  throw InputError("unknown MCAP compression \"" + std::string(name) + "\" (expected none, lz4 or zstd)");
}

}  // namespace uavmot::mcap
