#include "compression.hpp"

#include <cstring>
#include <string>

#include <lz4frame.h>
#include <zstd.h>

namespace uavmot::mcap::detail {

struct Codec::Contexts {
  ZSTD_CCtx* zstd_c = nullptr;
  ZSTD_DCtx* zstd_d = nullptr;
  LZ4F_dctx* lz4_d = nullptr;
  ~Contexts() {
    ZSTD_freeCCtx(zstd_c);
    ZSTD_freeDCtx(zstd_d);
    if (lz4_d) LZ4F_freeDecompressionContext(lz4_d);
  }
};

Codec::Codec() : contexts_(std::make_unique<Contexts>()) {}
Codec::~Codec() = default;

void Codec::compress(Compression compression, int level, int threads, const uint8_t* data, size_t size,
                     std::vector<uint8_t>& out) {
  switch (compression) {
    case Compression::None:
      out.assign(data, data + size);
      return;
    case Compression::Zstd: {
      if (!contexts_->zstd_c) {
        contexts_->zstd_c = ZSTD_createCCtx();
        // Level 1 keeps up with 60 Hz 1080p frames on one core; see docs/benchmarks/mcap.md.
        ZSTD_CCtx_setParameter(contexts_->zstd_c, ZSTD_c_compressionLevel, level == 0 ? 1 : level);
        ZSTD_CCtx_setParameter(contexts_->zstd_c, ZSTD_c_contentSizeFlag, 1);
        if (threads > 0) {
          const size_t r = ZSTD_CCtx_setParameter(contexts_->zstd_c, ZSTD_c_nbWorkers, threads);
          if (ZSTD_isError(r)) throw std::runtime_error(std::string("zstd: no worker threads: ") + ZSTD_getErrorName(r));
        }
      }
      out.resize(ZSTD_compressBound(size));
      const size_t n = ZSTD_compress2(contexts_->zstd_c, out.data(), out.size(), data, size);
      if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
      out.resize(n);
      return;
    }
    case Compression::Lz4: {
      LZ4F_preferences_t prefs;
      std::memset(&prefs, 0, sizeof prefs);
      prefs.frameInfo.blockSizeID = LZ4F_max4MB;
      prefs.frameInfo.contentSize = size;
      prefs.compressionLevel = level;
      out.resize(LZ4F_compressFrameBound(size, &prefs));
      const size_t n = LZ4F_compressFrame(out.data(), out.size(), data, size, &prefs);
      if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
      out.resize(n);
      return;
    }
  }
  throw std::runtime_error("unknown compression");
}

void Codec::decompress(std::string_view compression, const uint8_t* data, size_t size, uint8_t* out,
                       size_t out_size) {
  if (compression.empty()) {
    if (size != out_size) {
      throw std::runtime_error("uncompressed chunk holds " + std::to_string(size) + " bytes but declares " +
                               std::to_string(out_size));
    }
    if (size) std::memcpy(out, data, size);
    return;
  }
  if (compression == "zstd") {
    if (!contexts_->zstd_d) contexts_->zstd_d = ZSTD_createDCtx();
    const size_t n = ZSTD_decompressDCtx(contexts_->zstd_d, out, out_size, data, size);
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    if (n != out_size) {
      throw std::runtime_error("zstd data decompresses to " + std::to_string(n) + " bytes, chunk declares " +
                               std::to_string(out_size));
    }
    return;
  }
  if (compression == "lz4") {
    if (!contexts_->lz4_d) {
      if (LZ4F_isError(LZ4F_createDecompressionContext(&contexts_->lz4_d, LZ4F_VERSION))) {
        throw std::runtime_error("lz4: cannot create a decompression context");
      }
    }
    LZ4F_resetDecompressionContext(contexts_->lz4_d);
    size_t in_pos = 0;
    size_t out_pos = 0;
    for (;;) {
      size_t in_n = size - in_pos;
      size_t out_n = out_size - out_pos;
      const size_t hint = LZ4F_decompress(contexts_->lz4_d, out + out_pos, &out_n, data + in_pos, &in_n, nullptr);
      if (LZ4F_isError(hint)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(hint));
      in_pos += in_n;
      out_pos += out_n;
      if (hint == 0) {  // frame complete
        if (in_pos != size) throw std::runtime_error("lz4: bytes after the end of the frame");
        break;
      }
      if (in_n == 0 && out_n == 0) {
        throw std::runtime_error(out_pos == out_size ? "lz4 data decompresses to more bytes than the chunk declares"
                                                     : "lz4 frame is truncated");
      }
    }
    if (out_pos != out_size) {
      throw std::runtime_error("lz4 data decompresses to " + std::to_string(out_pos) + " bytes, chunk declares " +
                               std::to_string(out_size));
    }
    return;
  }
  throw std::runtime_error("unsupported chunk compression \"" + std::string(compression) + "\"");
}

}  // namespace uavmot::mcap::detail
