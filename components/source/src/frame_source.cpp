#include "uavmot/source/frame_source.hpp"

#include <algorithm>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <spdlog/spdlog.h>

#include "uavmot/core/error.hpp"
#include "uavmot/source/sequence_info.hpp"

namespace uavmot::source {
namespace fs = std::filesystem;
namespace {

bool has_image_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" || ext == ".tiff" ||
         ext == ".pgm" || ext == ".ppm";
}

cv::Mat to_color_mode(const cv::Mat& image, ColorMode mode) {
  if (mode == ColorMode::Gray) {
    if (image.channels() == 1) return image;
    cv::Mat gray;
    cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
    return gray;
  }
  if (image.channels() == 3) return image;
  cv::Mat color;
  cv::cvtColor(image, color, image.channels() == 4 ? cv::COLOR_BGRA2BGR : cv::COLOR_GRAY2BGR);
  return color;
}

int64_t time_ns(int64_t index, double fps) {
  return static_cast<int64_t>(static_cast<double>(index - 1) * 1e9 / fps + 0.5);
}

// Shared bookkeeping: start frame, frame limit, loop, numbering and timestamps.
class SourceBase : public FrameSource {
 public:
  explicit SourceBase(FrameSourceOptions options) : options_(std::move(options)) {}
  const SourceInfo& info() const override { return info_; }
  int64_t skipped() const override { return skipped_; }

  bool next(Frame& frame) override {
    if (options_.max_frames > 0 && delivered_ >= options_.max_frames) return false;
    cv::Mat image;
    if (!read_next(image)) {
      if (!options_.loop || delivered_ == 0) return false;
      rewind();
      if (!read_next(image)) return false;
    }
    ++delivered_;
    frame.stream_id = options_.stream_id;
    frame.index = delivered_;
    frame.capture_time_ns = time_ns(delivered_, info_.fps);
    frame.image = to_color_mode(image, options_.color);
    return true;
  }

  bool skip() override {
    if (options_.max_frames > 0 && delivered_ >= options_.max_frames) return false;
    if (!skip_next()) {
      if (!options_.loop || delivered_ == 0) return false;
      rewind();
      if (!skip_next()) return false;
    }
    ++delivered_;
    return true;
  }

 protected:
  // Reads the next input image (after start_frame); false at the end.
  virtual bool read_next(cv::Mat& image) = 0;
  // Moves past the next input image without decoding it; false at the end.
  virtual bool skip_next() = 0;
  virtual void rewind() = 0;

  FrameSourceOptions options_;
  SourceInfo info_;
  int64_t skipped_ = 0;

 private:
  int64_t delivered_ = 0;
};

class ImageListSource : public SourceBase {
 public:
  ImageListSource(FrameSourceOptions options, std::vector<fs::path> files, std::string kind, double fps, double gsd)
      : SourceBase(std::move(options)), files_(std::move(files)) {
    if (options_.start_frame > static_cast<int64_t>(files_.size())) {
      throw InputError("start frame " + std::to_string(options_.start_frame) + " is beyond the " +
                       std::to_string(files_.size()) + " images of '" + options_.path + "'");
    }
    info_.kind = std::move(kind);
    info_.fps = options_.fps_override > 0.0 ? options_.fps_override : fps;
    info_.gsd_m = gsd;
    int64_t available = static_cast<int64_t>(files_.size()) - (options_.start_frame - 1);
    info_.frame_count = options_.max_frames > 0 ? std::min(available, options_.max_frames) : available;
    rewind();
    // Decode the first image now so a broken input fails before anything is published.
    const cv::Mat first = cv::imread(files_[next_].string(), cv::IMREAD_UNCHANGED);
    if (!first.empty()) info_.size = first.size();
    else if (!options_.skip_corrupt) throw InputError("cannot decode image '" + files_[next_].string() + "'");
  }

 protected:
  bool read_next(cv::Mat& image) override {
    while (next_ < files_.size()) {
      const fs::path& file = files_[next_++];
      image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
      if (!image.empty() && image.depth() == CV_8U) {
        if (info_.size.empty()) info_.size = image.size();
        if (image.size() != info_.size) {
          throw InputError("image '" + file.string() + "' is " + std::to_string(image.cols) + "x" +
                           std::to_string(image.rows) + ", the sequence is " + std::to_string(info_.size.width) + "x" +
                           std::to_string(info_.size.height));
        }
        return true;
      }
      const std::string why = image.empty() ? "cannot decode image" : "unsupported pixel depth (8-bit expected) in";
      if (!options_.skip_corrupt) throw InputError(why + " '" + file.string() + "'");
      spdlog::warn("{} '{}': skipped", why, file.string());
      ++skipped_;
    }
    return false;
  }
  bool skip_next() override {
    if (next_ >= files_.size()) return false;
    ++next_;
    return true;
  }
  void rewind() override { next_ = static_cast<size_t>(options_.start_frame - 1); }

 private:
  std::vector<fs::path> files_;
  size_t next_ = 0;
};

class VideoSource : public SourceBase {
 public:
  explicit VideoSource(FrameSourceOptions options) : SourceBase(std::move(options)) {
    open();
    info_.kind = "video";
    const double fps = capture_.get(cv::CAP_PROP_FPS);
    info_.fps = options_.fps_override > 0.0 ? options_.fps_override : (fps > 0.0 && fps < 1000.0 ? fps : 25.0);
    expected_frames_ = static_cast<int64_t>(capture_.get(cv::CAP_PROP_FRAME_COUNT));
    info_.size = {static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_WIDTH)),
                  static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_HEIGHT))};
    if (expected_frames_ > 0) {
      const int64_t available = std::max<int64_t>(0, expected_frames_ - (options_.start_frame - 1));
      info_.frame_count = options_.max_frames > 0 ? std::min(available, options_.max_frames) : available;
    }
    rewind();
  }

 protected:
  bool read_next(cv::Mat& image) override {
    if (!capture_.read(image) || image.empty()) {
      // A container that promised more frames than it decodes is truncated or corrupt.
      // The frames read so far were delivered; the caller reports this as an error.
      if (expected_frames_ > 0 && position_ < expected_frames_ - 1 && !options_.loop) {
        throw InputError("video '" + options_.path + "' ended after " + std::to_string(position_) + " of " +
                         std::to_string(expected_frames_) + " frames: the file is truncated or corrupt");
      }
      return false;
    }
    ++position_;
    return true;
  }
  bool skip_next() override {
    // grab() demuxes (and, for inter-coded streams, decodes) but skips the conversion to a Mat.
    if (!capture_.grab()) return false;
    ++position_;
    return true;
  }
  void rewind() override {
    if (position_ != 0) open();
    position_ = 0;
    cv::Mat skip;
    for (int64_t i = 1; i < options_.start_frame; ++i) {
      if (!capture_.read(skip)) {
        throw InputError("start frame " + std::to_string(options_.start_frame) + " is beyond the end of '" +
                         options_.path + "'");
      }
      ++position_;
    }
  }

 private:
  void open() {
    capture_.release();
    if (!capture_.open(options_.path, cv::CAP_FFMPEG)) {
      throw InputError("cannot open video '" + options_.path + "' (not a video, or truncated/corrupt)");
    }
  }
  cv::VideoCapture capture_;
  int64_t expected_frames_ = 0;
  int64_t position_ = 0;
};

std::vector<fs::path> list_images(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && has_image_extension(entry.path())) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

ColorMode parse_color_mode(const std::string& name) {
  if (name == "gray") return ColorMode::Gray;
  if (name == "color") return ColorMode::Color;
  throw InvalidArgument("unknown colour mode '" + name + "' (expected gray or color)");
}

std::unique_ptr<FrameSource> open_frame_source(const FrameSourceOptions& options) {
  if (options.start_frame < 1) throw InputError("start frame must be >= 1");
  if (options.max_frames < 0) throw InputError("frame count must be >= 0");
  const fs::path path(options.path);
  std::error_code ec;
  if (options.path.empty() || !fs::exists(path, ec)) throw InputError("input '" + options.path + "' does not exist");
  if (fs::is_directory(path)) {
    if (is_mot_sequence(options.path)) {
      const SequenceInfo seq = read_sequence_info(options.path);
      const fs::path image_dir = path / seq.image_dir;
      if (!fs::is_directory(image_dir)) throw InputError("sequence '" + options.path + "' has no folder '" + seq.image_dir + "'");
      auto files = list_images(image_dir);
      if (files.empty()) throw InputError("no images in '" + image_dir.string() + "'");
      return std::make_unique<ImageListSource>(options, std::move(files), "mot", seq.frame_rate, seq.gsd_m);
    }
    auto files = list_images(path);
    if (files.empty()) throw InputError("no images (png, jpg, bmp, tif, pgm) in folder '" + options.path + "'");
    return std::make_unique<ImageListSource>(options, std::move(files), "images", 25.0, 0.0);
  }
  if (fs::file_size(path, ec) == 0) throw InputError("input '" + options.path + "' is empty");
  return std::make_unique<VideoSource>(options);
}

}  // namespace uavmot::source
