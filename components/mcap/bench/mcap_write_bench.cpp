// Recording throughput: 1080p mono8 frames (2 MB) written as fast as possible with each chunk
// compression, then read back. Frames are mosaics of real CLIF 2007 pixels at their native
// resolution (three 640x1004 crops side by side over three 640x76 strips of three more), so the
// compression ratio is that of real aerial imagery, not of resampled or synthetic images.
//
//   mcap_write_bench [--frames N] [--data DIR] [--out DIR] [--chunk-size BYTES] [--zstd-level L]
//                    [--zstd-threads T] [--paced HZ]
// --paced HZ adds a second table: frames offered at HZ through a QueuedWriter (256 MB queue,
// never waiting, as a DDS callback would) with the frames dropped and the queue's high-water mark.
//
// Prints one table row per compression: MB/s, CPU ms per frame, ratio, read-back MB/s.
// 60 Hz recording of 2 MB frames needs >= 120 MB/s sustained.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/mcap/queued_writer.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/mcap/writer.hpp"

namespace {

using namespace uavmot::mcap;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::vector<std::vector<uint8_t>> load_mosaics(const std::string& dir, int count) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() == ".jpg") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.size() < 6) throw std::runtime_error(dir + ": needs at least 6 .jpg frames");
  std::vector<cv::Mat> gray;
  for (size_t i = 0; i < files.size() && static_cast<int>(i) < count + 6; ++i) {
    cv::Mat m = cv::imread(files[i].string(), cv::IMREAD_GRAYSCALE);
    if (m.empty() || m.cols < 640 || m.rows < 1004) throw std::runtime_error(files[i].string() + ": unexpected frame");
    gray.push_back(m);
  }
  std::vector<std::vector<uint8_t>> mosaics;
  for (int k = 0; k < count; ++k) {
    cv::Mat mosaic(1080, 1920, CV_8UC1);
    const auto at = [&](int j) -> const cv::Mat& { return gray[(k + j) % gray.size()]; };
    for (int j = 0; j < 3; ++j) at(j)(cv::Rect(0, 0, 640, 1004)).copyTo(mosaic(cv::Rect(640 * j, 0, 640, 1004)));
    for (int j = 0; j < 3; ++j) {
      at(3 + j)(cv::Rect(0, 500, 640, 76)).copyTo(mosaic(cv::Rect(640 * j, 1004, 640, 76)));
    }
    std::vector<uint8_t> payload(100, 0);  // stands for the CDR header and Frame fields
    payload[1] = 1;
    payload.insert(payload.end(), mosaic.datastart, mosaic.dataend);
    mosaics.push_back(std::move(payload));
  }
  return mosaics;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 240;
  std::string data = uavmot::build_paths::data_dir() + "/clif2007/jpg";
  std::string out = "/tmp/uavmot_mcap_bench";
  uint64_t chunk_size = 4ull << 20;
  int zstd_level = 0;
  int zstd_threads = 0;
  double paced_hz = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const std::string value = argv[i + 1];
    if (key == "--frames") frames = std::stoi(value);
    else if (key == "--data") data = value;
    else if (key == "--out") out = value;
    else if (key == "--chunk-size") chunk_size = std::stoull(value);
    else if (key == "--zstd-level") zstd_level = std::stoi(value);
    else if (key == "--zstd-threads") zstd_threads = std::stoi(value);
    else if (key == "--paced") paced_hz = std::stod(value);
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  try {
    std::filesystem::create_directories(out);
    const auto mosaics = load_mosaics(data, std::min(frames, 120));
    const double raw_mb = static_cast<double>(mosaics[0].size()) * frames / 1e6;
    std::printf("%d frames of %zu bytes (1920x1080 mono8 + 100 B header), %.0f MB, chunk %llu bytes\n\n", frames,
                mosaics[0].size(), raw_mb, static_cast<unsigned long long>(chunk_size));
    std::printf("| compression | write MB/s | write CPU ms/frame | max fps (CPU) | file MB | ratio | close+sync s | read MB/s | read CPU ms/frame |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (Compression c : {Compression::None, Compression::Lz4, Compression::Zstd}) {
      const std::string path = out + "/bench_" + std::string(c == Compression::None ? "none" : compression_name(c)) + ".mcap";
      WriterOptions options;
      options.compression = c;
      options.chunk_size = chunk_size;
      options.compression_level = c == Compression::Zstd ? zstd_level : 0;
      options.compression_threads = c == Compression::Zstd ? zstd_threads : 0;
      Writer writer(options);
      writer.open(path);
      const uint16_t channel = writer.add_channel(0, "uavmot/frames", "cdr");
      const double w0 = wall_seconds();
      const double c0 = cpu_seconds();
      for (int i = 0; i < frames; ++i) {
        const auto& f = mosaics[i % mosaics.size()];
        const uint64_t t = 1'000'000'000ull + static_cast<uint64_t>(i) * 16'666'667ull;
        writer.write(channel, static_cast<uint32_t>(i), t, t, f.data(), f.size());
      }
      writer.close();
      const double w1 = wall_seconds();
      const double c1 = cpu_seconds();
      ::sync();
      const double w2 = wall_seconds();
      const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;

      Reader reader;
      const double r0 = wall_seconds();
      const double rc0 = cpu_seconds();
      reader.open(path);
      uint64_t bytes = 0;
      reader.for_each_message({}, [&](const MessageView& m) {
        bytes += m.size;
        return true;
      });
      const double r1 = wall_seconds();
      const double rc1 = cpu_seconds();
      if (bytes != mosaics[0].size() * static_cast<uint64_t>(frames)) throw std::runtime_error("read-back mismatch");

      const double cpu_ms = (c1 - c0) * 1e3 / frames;
      std::printf("| %s | %.0f | %.2f | %.0f | %.0f | %.2f | %.2f | %.0f | %.2f |\n",
                  c == Compression::None ? "none" : std::string(compression_name(c)).c_str(), raw_mb / (w1 - w0),
                  cpu_ms, 1e3 / cpu_ms, file_mb, raw_mb / file_mb, w2 - w1, raw_mb / (r1 - r0),
                  (rc1 - rc0) * 1e3 / frames);
      std::fflush(stdout);
      std::filesystem::remove(path);
    }
    if (paced_hz > 0) {
      std::printf("\n%d frames offered at %.0f Hz through QueuedWriter (queue 256 MB, drop when full)\n\n", frames,
                  paced_hz);
      std::printf("| compression | frames written | dropped | max queue MB | drain after last frame s | CPU ms/frame |\n");
      std::printf("|---|---|---|---|---|---|\n");
      for (Compression c : {Compression::None, Compression::Lz4, Compression::Zstd}) {
        const std::string name = c == Compression::None ? "none" : std::string(compression_name(c));
        const std::string path = out + "/paced_" + name + ".mcap";
        WriterOptions options;
        options.compression = c;
        options.chunk_size = chunk_size;
        options.compression_level = c == Compression::Zstd ? zstd_level : 0;
        options.compression_threads = c == Compression::Zstd ? zstd_threads : 0;
        QueuedWriter writer(options);
        writer.open(path);
        const uint16_t channel = writer.add_channel(0, "uavmot/frames", "cdr");
        const double c0 = cpu_seconds();
        const auto start = std::chrono::steady_clock::now();
        const auto period = std::chrono::duration<double>(1.0 / paced_hz);
        for (int i = 0; i < frames; ++i) {
          std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(period * i));
          const auto& f = mosaics[i % mosaics.size()];
          const uint64_t t = 1'000'000'000ull + static_cast<uint64_t>(i * 1e9 / paced_hz);
          writer.write(channel, static_cast<uint32_t>(i), t, t, f, /*wait_when_full=*/false);
        }
        const double last = wall_seconds();
        writer.close();
        const double drained = wall_seconds();
        const double c1 = cpu_seconds();
        std::printf("| %s | %llu | %llu | %.0f | %.2f | %.2f |\n", name.c_str(),
                    static_cast<unsigned long long>(writer.statistics().message_count),
                    static_cast<unsigned long long>(writer.dropped()), writer.max_queued_bytes() / 1e6,
                    drained - last, (c1 - c0) * 1e3 / frames);
        std::fflush(stdout);
        std::filesystem::remove(path);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mcap_write_bench: %s\n", e.what());
    return 1;
  }
}
