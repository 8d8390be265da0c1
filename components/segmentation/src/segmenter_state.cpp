// Segmenter::save_state / restore_state: the shift check's windows of the frame segmented last.
//
// Layout, little-endian:
//   magic "USEGSTAT" (8 bytes) | u32 version | u64 payload bytes | u64 FNV-1a 64 of the payload | payload
// Payload (version 1):
//   u64 stream bytes | stream | i64 frame index (-1: none) |
//   u64 windows, each: i32 x | i32 y | i32 width | i32 height | width*height grey bytes (row-major)
// No options fingerprint: the windows are pixels of the frame, usable under any options.

#include <cstring>

#include "uavmot/core/checksum.hpp"
#include "uavmot/core/state_codec.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot::segmentation {
namespace {

constexpr char kStateMagic[8] = {'U', 'S', 'E', 'G', 'S', 'T', 'A', 'T'};
constexpr uint32_t kStateVersion = 1;
constexpr size_t kStateHeaderBytes = 8 + 4 + 8 + 8;
constexpr int kMaxWindowSide = 1 << 15;

}  // namespace

std::vector<uint8_t> Segmenter::save_state() const {
  state_codec::Writer w;
  w.put(static_cast<uint64_t>(previous_stream_.size()));
  w.put_bytes(previous_stream_.data(), previous_stream_.size());
  w.put(previous_frame_);
  w.put(static_cast<uint64_t>(previous_windows_.size()));
  for (const ImageCrop& crop : previous_windows_) {
    w.put(static_cast<int32_t>(crop.roi.x));
    w.put(static_cast<int32_t>(crop.roi.y));
    w.put(static_cast<int32_t>(crop.pixels.cols));
    w.put(static_cast<int32_t>(crop.pixels.rows));
    for (int y = 0; y < crop.pixels.rows; ++y) w.put_bytes(crop.pixels.ptr<uint8_t>(y), static_cast<size_t>(crop.pixels.cols));
  }
  const std::vector<uint8_t>& payload = w.bytes();
  state_codec::Writer out;
  out.reserve(kStateHeaderBytes + payload.size());
  out.put_bytes(kStateMagic, sizeof kStateMagic);
  out.put(kStateVersion);
  out.put(static_cast<uint64_t>(payload.size()));
  out.put(fnv1a64(payload.data(), payload.size()));
  out.put_bytes(payload.data(), payload.size());
  return std::move(out.bytes());
}

void Segmenter::restore_state(const std::vector<uint8_t>& bytes) {
  const std::string what = "segmentation state";
  state_codec::Reader header(bytes.data(), bytes.size(), what);
  if (bytes.size() < sizeof kStateMagic || std::memcmp(bytes.data(), kStateMagic, sizeof kStateMagic) != 0) {
    header.fail("not a segmentation state (no 'USEGSTAT' at the start)");
  }
  header.get_bytes(sizeof kStateMagic);
  const auto version = header.get<uint32_t>();
  if (version != kStateVersion) {
    header.fail("format version " + std::to_string(version) + ", this build reads version " + std::to_string(kStateVersion));
  }
  const auto payload_size = header.get<uint64_t>();
  const auto checksum = header.get<uint64_t>();
  if (payload_size != header.remaining()) {
    header.fail("truncated or padded: " + std::to_string(header.remaining()) + " payload bytes, the header says " +
                std::to_string(payload_size));
  }
  const uint8_t* payload = bytes.data() + kStateHeaderBytes;
  if (fnv1a64(payload, payload_size) != checksum) header.fail("corrupt (checksum mismatch)");

  state_codec::Reader r(payload, payload_size, what);
  const uint64_t stream_bytes = r.get_count(1);
  const auto* stream = reinterpret_cast<const char*>(r.get_bytes(stream_bytes));
  const auto frame = r.get<int64_t>();
  if (frame < -1) r.fail("frame index " + std::to_string(frame));
  std::vector<ImageCrop> windows(r.get_count(16));
  for (ImageCrop& crop : windows) {
    const int x = r.get<int32_t>(), y = r.get<int32_t>(), width = r.get<int32_t>(), height = r.get<int32_t>();
    if (x < 0 || y < 0 || width < 1 || height < 1 || width > kMaxWindowSide || height > kMaxWindowSide) {
      r.fail("a window at (" + std::to_string(x) + ", " + std::to_string(y) + ") of " + std::to_string(width) + " x " +
             std::to_string(height) + " px");
    }
    const uint8_t* pixels = r.get_bytes(static_cast<size_t>(width) * static_cast<size_t>(height));
    crop.roi = cv::Rect(x, y, width, height);
    crop.pixels = cv::Mat(height, width, CV_8UC1);
    std::memcpy(crop.pixels.data, pixels, static_cast<size_t>(width) * static_cast<size_t>(height));
  }
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the last window");
  previous_stream_.assign(stream, stream_bytes);
  previous_frame_ = frame;
  previous_windows_ = std::move(windows);
}

}  // namespace uavmot::segmentation
