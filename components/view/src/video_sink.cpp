#include "uavmot/view/video_sink.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "uavmot/core/error.hpp"

namespace uavmot::view {
namespace fs = std::filesystem;

VideoSink::VideoSink(VideoSinkOptions options) : options_(std::move(options)) {
  if (options_.path.empty()) throw InputError("video output: no file name given");
  if (!(options_.fps > 0) || !std::isfinite(options_.fps)) {
    throw InputError(fmt::format("video output '{}': frame rate must be > 0 (got {})", options_.path, options_.fps));
  }
  if (options_.fourcc.size() != 4) throw InputError(fmt::format("video output '{}': fourcc must have 4 characters", options_.path));
  const fs::path path(options_.path);
  if (fs::is_directory(path)) throw InputError(fmt::format("video output '{}' is a folder, not a file", options_.path));
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  if (ec) throw InputError(fmt::format("video output '{}': cannot create its folder: {}", options_.path, ec.message()));
  // Fail now, with the reason, rather than at the first frame deep inside the encoder.
  std::ofstream probe(path, std::ios::binary | std::ios::trunc);
  if (!probe) throw InputError(fmt::format("video output '{}' cannot be written", options_.path));
}

VideoSink::~VideoSink() { close(); }

void VideoSink::write(const cv::Mat& frame) {
  if (frame.empty()) throw InvalidArgument(fmt::format("video output '{}': empty frame", options_.path));
  if (!writer_) {
    size_ = frame.size();
    writer_ = std::make_unique<cv::VideoWriter>();
    const auto& c = options_.fourcc;
    // OpenCV passes this variable to the encoder as "key;value|key;value" (its FFmpeg backend reads it
    // at open); a user's own setting wins.
    if (c == "avc1" && !options_.h264_preset.empty()) {
      setenv("OPENCV_FFMPEG_WRITER_OPTIONS", ("preset;" + options_.h264_preset).c_str(), 0);
    }
    writer_->open(options_.path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc(c[0], c[1], c[2], c[3]), options_.fps, size_, true);
    if (!writer_->isOpened()) {
      writer_.reset();
      throw InputError(fmt::format("video output '{}': cannot open an {} encoder for {}x{} at {} fps", options_.path, c,
                                   size_.width, size_.height, options_.fps));
    }
  }
  cv::Mat bgr;
  if (frame.channels() == 1) cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
  else bgr = frame;
  if (bgr.size() != size_) cv::resize(bgr, bgr, size_, 0, 0, cv::INTER_AREA);
  writer_->write(bgr);
  ++frames_;
}

void VideoSink::close() {
  if (writer_) {
    writer_->release();
    writer_.reset();
  } else if (frames_ == 0 && !closed_) {
    // Nothing came: leave no empty file that players would call broken.
    std::error_code ec;
    fs::remove(options_.path, ec);
  }
  closed_ = true;
}

}  // namespace uavmot::view
