#pragma once
// Writes annotated frames to an mp4 file through OpenCV's FFmpeg backend: H.264 (fourcc avc1,
// libx264, yuv420p) by default, which browsers play; mp4v (MPEG-4 Part 2) on request. The size is
// taken from the first frame.

#include <cstdint>
#include <memory>
#include <string>

#include <opencv2/core/mat.hpp>

namespace cv {
class VideoWriter;
}

namespace uavmot::view {

struct VideoSinkOptions {
  std::string path;            // e.g. out.mp4; its folder is created if missing
  double fps = 25.0;
  std::string fourcc = "avc1";  // "avc1" (H.264) or "mp4v"
  // libx264 preset for avc1 (OPENCV_FFMPEG_WRITER_OPTIONS, when the user has not set it): veryfast
  // keeps up with the chain; slower presets only shrink the file.
  std::string h264_preset = "veryfast";
};

class VideoSink {
 public:
  // Throws InputError naming the path when it cannot be written (folder not creatable, not writable).
  explicit VideoSink(VideoSinkOptions options);
  ~VideoSink();  // closes the file
  VideoSink(const VideoSink&) = delete;
  VideoSink& operator=(const VideoSink&) = delete;

  // Appends one frame (mono8 or bgr8). Frames of another size than the first are resized to it.
  // Throws InputError when the encoder cannot be opened for this file.
  void write(const cv::Mat& frame);
  // Finishes the file (idempotent). Frames written before are all in it; with none, no file is left.
  void close();

  int64_t frames_written() const { return frames_; }
  const std::string& path() const { return options_.path; }

 private:
  VideoSinkOptions options_;
  std::unique_ptr<cv::VideoWriter> writer_;
  cv::Size size_;
  int64_t frames_ = 0;
  bool closed_ = false;
};

}  // namespace uavmot::view
