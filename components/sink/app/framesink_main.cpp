// uavmot-framesink: subscribes to uavmot/frames and writes what it received: one line per frame
// with its checksum (frames.csv), and optionally the images. Ends at each stream's end-of-stream.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <spdlog/spdlog.h>

#include "framePubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/checksum.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/frame_convert.hpp"
#include "uavmot/dds/health_reporter.hpp"
#include "uavmot/dds/node_options.hpp"

namespace uavmot {
namespace {

int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

int framesink_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string out_dir;
  bool save_images = false;
  int streams = 1;
  double idle_timeout_s = 60.0;

  return run_app(argc, argv, "framesink", "write received frames (checksums, optionally images)", [&](CLI::App& app) {
    app.add_option("--out", out_dir, "output folder (frames.csv, images/)")->required();
    app.add_flag("--save-images", save_images, "also write every frame as PNG");
    app.add_option("--streams", streams, "end after this many streams sent end-of-stream")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--idle-timeout", idle_timeout_s, "fail if no sample arrives for this long (s)")->capture_default_str();
    dds::add_node_options(app, node);

    return [&]() -> int {
      dds::finalize(node, "framesink");
      install_shutdown_handler();
      namespace fs = std::filesystem;
      std::error_code ec;
      fs::create_directories(fs::path(out_dir) / (save_images ? "images" : ""), ec);
      if (ec) throw InputError("cannot create '" + out_dir + "': " + ec.message());
      std::ofstream csv(fs::path(out_dir) / "frames.csv");
      if (!csv) throw InputError("cannot write '" + out_dir + "/frames.csv'");
      csv << "stream_id,frame_index,capture_time_ns,width,height,channels,bytes,fnv1a64,receive_time_ns,source_time_ns\n";

      dds::Participant participant(node.dds);
      auto reader = participant.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
      dds::HealthReporter health(participant, "framesink", "*");
      health.watch(*reader);
      std::set<std::string> finished;
      uint64_t received = 0;
      auto last_sample = std::chrono::steady_clock::now();
      msg::Frame sample;
      eprosima::fastdds::dds::SampleInfo info;
      while (!shutdown_requested() && static_cast<int>(finished.size()) < streams) {
        if (!reader->wait_for_data(std::chrono::milliseconds(200))) {
          health.tick();
          if (std::chrono::steady_clock::now() - last_sample > std::chrono::duration<double>(idle_timeout_s)) {
            spdlog::error("no frame for {} s; {} received", idle_timeout_s, received);
            return kExitFailure;
          }
          continue;
        }
        while (reader->take(sample, &info)) {
          last_sample = std::chrono::steady_clock::now();
          if (sample.end_of_stream()) {
            finished.insert(sample.stream_id().to_string());
            spdlog::info("stream '{}' ended after frame {}", sample.stream_id().to_string(), sample.frame_index());
            continue;
          }
          std::string why;
          const auto frame = dds::from_msg(sample, why);
          health.frame_in();
          if (!frame) {
            health.invalid_sample();
            spdlog::warn("dropped a malformed frame sample: {}", why);
            continue;
          }
          const size_t bytes = frame->image.total() * frame->image.elemSize();
          const int64_t source_ns = static_cast<int64_t>(info.source_timestamp.seconds()) * 1'000'000'000LL +
                                    info.source_timestamp.nanosec();
          csv << fmt::format("{},{},{},{},{},{},{},{:016x},{},{}\n", frame->stream_id, frame->index,
                             frame->capture_time_ns, frame->image.cols, frame->image.rows, frame->image.channels(), bytes,
                             fnv1a64(frame->image.data, bytes), wall_ns(), source_ns);
          if (save_images) {
            cv::imwrite((fs::path(out_dir) / "images" / fmt::format("{}_{:06d}.png", frame->stream_id, frame->index)).string(),
                        frame->image);
          }
          ++received;
          health.frame_out(frame->index, 0.0);
          health.tick();
        }
      }
      csv.close();
      health.report(msg::ComponentState::FINISHED);
      spdlog::info("received {} frames from {} stream(s)", received, finished.size());
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::framesink_main(argc, argv); }
