// Segmenter::save_state / restore_state: the shift check's windows of the frame segmented last.
//
// Layout, little-endian: state_codec::seal's envelope (magic "USEGSTAT", version, size, checksum)
// around the payload. Payload (version 1):
//   u64 stream bytes | stream | i64 frame index (-1: none) |
//   u64 windows, each: i32 x | i32 y | i32 width | i32 height | width*height grey bytes (row-major)
// No options fingerprint: the windows are pixels of the frame, usable under any options.

#include <cstring>

#include "uavmot/core/state_codec.hpp"
#include "uavmot/segmentation/segmenter.hpp"

namespace uavmot::segmentation {
namespace {

constexpr char kStateMagic[8] = {'U', 'S', 'E', 'G', 'S', 'T', 'A', 'T'};
constexpr uint32_t kStateVersion = 1;
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
  return state_codec::seal(kStateMagic, kStateVersion, w.bytes());
}

void Segmenter::restore_state(const std::vector<uint8_t>& bytes) {
  state_codec::Reader r = state_codec::unseal(bytes, kStateMagic, kStateVersion, "segmentation state", "segmentation state");
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
