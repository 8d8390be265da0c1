// uavmot-record: subscribes to uavmot topics and writes every sample to MCAP, CDR bytes as on
// the wire (docs/record.md). `--recover FILE.mcap.tmp` makes a valid file of a crashed recording.

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <thread>

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/mcap/queued_writer.hpp"
#include "uavmot/mcap/recover.hpp"
#include "uavmot/foxglove/schemas.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/record/foxglove_translation.hpp"
#include "uavmot/record/qos_description.hpp"
#include "uavmot/record/topic_catalog.hpp"
#include "uavmot/record/typed_topic.hpp"

namespace uavmot {
namespace {

uint64_t wall_ns() {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

uint64_t to_ns(const eprosima::fastrtps::rtps::Time_t& t) {
  if (t.seconds() < 0) return 0;
  return static_cast<uint64_t>(t.seconds()) * 1000000000ull + t.nanosec();
}

// One recorded topic: takes typed samples and queues their CDR bytes.
class TopicRecorder {
 public:
  virtual ~TopicRecorder() = default;
  // Takes every waiting sample; returns how many.
  virtual size_t drain() = 0;
  virtual bool wait_for_data(std::chrono::milliseconds timeout) = 0;
  virtual const std::string& topic() const = 0;
  uint64_t recorded() const { return sequence_; }
  // Per stream of a chain topic: first and last frame index recorded and the indices missing in
  // between (skipped upstream, or lost), so a log tells at once whether a recording is complete.
  std::string coverage() const {
    std::string out;
    for (const auto& [stream, c] : coverage_) {
      out += fmt::format("; stream {}: frames {}..{}, {} missing", stream, c.first, c.last, c.missing);
    }
    return out;
  }

 protected:
  template <class Sample>
  void note_frame(const Sample& sample) {
    if constexpr (requires { sample.frame_index(); sample.end_of_stream(); }) {
      if (sample.end_of_stream()) return;
      auto [it, fresh] = coverage_.try_emplace(sample.stream_id().to_string());
      Coverage& c = it->second;
      const int64_t index = sample.frame_index();
      if (fresh) c.first = index;
      else if (index > c.last + 1) c.missing += static_cast<uint64_t>(index - c.last - 1);
      c.last = std::max(c.last, index);
    }
  }

  uint32_t sequence_ = 0;

 private:
  struct Coverage {
    int64_t first = 0, last = 0;
    uint64_t missing = 0;
  };
  std::map<std::string, Coverage> coverage_;
};

template <class PubSubType>
class TypedRecorder final : public TopicRecorder {
 public:
  // `foxglove`: also write the Foxglove-schema channel this topic feeds (null: none).
  TypedRecorder(dds::Participant& participant, const record::TopicSpec& spec, const std::string& idl_dir,
                dds::DeliveryMode chain_mode, mcap::QueuedWriter& out, const record::FoxgloveOptions* foxglove)
      : reader_(spec.topic_class == dds::TopicClass::Frames
                    // Room for many frames: a live writer keeps only its last 2, so a moment in
                    // which this thread gets no CPU must not fill the reader's queue.
                    ? participant.make_reader<PubSubType>(spec.topic, std::string("frames_record_reader"))
                    : participant.make_reader<PubSubType>(spec.topic, spec.topic_class)),
        out_(out) {
    const auto qos = record::describe_qos(reader_->native()->get_qos());
    channel_ = out_.add_channel(out_.add_schema(spec.type_name, "omgidl", record::schema_text(spec, idl_dir)), spec.topic,
                                "cdr", record::channel_metadata(spec, chain_mode, qos));
    if (const auto fc = foxglove ? record::foxglove_channel(spec.topic, *foxglove) : std::nullopt) {
      foxglove_ = *foxglove;
      foxglove_channel_ = out_.add_channel(
          out_.add_schema(fc->schema_name, "omgidl", foxglove::schema_text(fc->schema_name, idl_dir)), fc->topic, "cdr",
          {{"topic", fc->topic}, {"type", fc->schema_name}, {"source_topic", spec.topic}});
    }
  }

  size_t drain() override {
    size_t n = 0;
    eprosima::fastdds::dds::SampleInfo info;
    while (reader_->take(sample_, &info)) {
      const uint64_t received = wall_ns();
      out_.write(channel_, ++sequence_, received, to_ns(info.source_timestamp), dds::to_cdr(type_, sample_));
      note_frame(sample_);
      if (foxglove_channel_) write_foxglove(received, to_ns(info.source_timestamp));
      ++n;
    }
    return n;
  }
  bool wait_for_data(std::chrono::milliseconds timeout) override { return reader_->wait_for_data(timeout); }
  const std::string& topic() const override { return reader_->topic(); }

 private:
  void write_foxglove(uint64_t received, uint64_t published) {
    std::string why;
    if (auto bytes = record::to_foxglove(sample_, foxglove_, why)) {
      out_.write(foxglove_channel_, ++foxglove_sequence_, received, published, std::move(*bytes));
    } else if (!why.empty()) {
      spdlog::warn("{}: no Foxglove message: {}", reader_->topic(), why);
    }
  }

  std::unique_ptr<dds::TopicReader<PubSubType>> reader_;
  mcap::QueuedWriter& out_;
  PubSubType type_;
  typename PubSubType::type sample_;  // reused: frames keep their pixel buffer between takes
  uint16_t channel_ = 0;
  record::FoxgloveOptions foxglove_;
  uint16_t foxglove_channel_ = 0;  // 0: none
  uint32_t foxglove_sequence_ = 0;
};

std::string recovered_name(const std::string& input) {
  const std::string suffix = ".tmp";
  if (input.size() > suffix.size() && input.compare(input.size() - suffix.size(), suffix.size(), suffix) == 0) {
    return input.substr(0, input.size() - suffix.size());
  }
  return input + ".recovered.mcap";
}

int recover_file(const std::string& input, std::string out) {
  if (out.empty()) out = recovered_name(input);
  const auto result = mcap::recover(input, out);
  for (const auto& d : result.damage) spdlog::warn("{}", d.description);
  spdlog::info("recovered {} messages on {} channels into {}", result.messages, result.channels, out);
  return kExitOk;
}

int record_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::vector<std::string> topics, exclude;
  std::string out, compression = "zstd", recover_input;
  double duration_s = 0.0;
  uint64_t queue_mb = 256, chunk_kb = 4096;
  bool with_foxglove = true;
  std::string image_format = "jpeg";
  record::FoxgloveOptions foxglove_options;
  return run_app(argc, argv, "record", "record uavmot topics to an MCAP file (CDR as on the wire)", [&](CLI::App& app) {
    app.add_option("--topics", topics, "topics or wildcard patterns to record (default: every uavmot topic)");
    app.add_option("--exclude", exclude, "topics or wildcard patterns not to record");
    app.add_option("--out", out, "the MCAP file to write (FILE.tmp until it is closed)");
    app.add_option("--compression", compression, "chunk compression")
        ->check(CLI::IsMember({"zstd", "lz4", "none"}))
        ->capture_default_str();
    app.add_option("--duration", duration_s, "stop after this many seconds (default: until Ctrl-C / SIGTERM)")
        ->check(uavmot::non_negative_finite());
    app.add_option("--queue-mb", queue_mb, "MiB of samples waiting for the disk before the recorder holds back")
        ->check(uavmot::positive_finite())
        ->capture_default_str();
    app.add_option("--chunk-kb", chunk_kb, "MCAP chunk size, KiB")->check(uavmot::positive_finite())->capture_default_str();
    app.add_flag("--foxglove,!--no-foxglove", with_foxglove,
                 "also write Foxglove-schema channels: uavmot/foxglove/image, tracks, regions, features (docs/foxglove.md)")
        ->capture_default_str();
    app.add_option("--image-format", image_format, "uavmot/foxglove/image as jpeg (CompressedImage) or raw (RawImage)")
        ->check(CLI::IsMember({"jpeg", "raw"}))
        ->capture_default_str();
    app.add_option("--jpeg-quality", foxglove_options.jpeg_quality, "JPEG quality of uavmot/foxglove/image")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--gsd", foxglove_options.style.gsd_m, "ground sampling distance, m/px (> 0: track labels in km/h)")
        ->check(uavmot::non_negative_finite());
    app.add_option("--fps", foxglove_options.style.fps, "frame rate, for km/h")->check(uavmot::positive_finite())->capture_default_str();
    app.add_option("--recover", recover_input, "make a valid MCAP of a crashed recording (FILE.mcap.tmp) and exit");
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "record");
      if (!recover_input.empty()) return recover_file(recover_input, out);
      if (out.empty()) throw InvalidArgument("--out FILE.mcap is required (or --recover FILE)");
      const auto chosen = record::select_topics(topics, exclude);
      const std::string idl_dir = record::find_idl_dir();
      foxglove_options.image_format = foxglove::parse_image_format(image_format);
      install_shutdown_handler();

      mcap::WriterOptions writer_options;
      writer_options.compression = mcap::parse_compression(compression);
      writer_options.chunk_size = chunk_kb * 1024;
      mcap::QueuedWriter writer(writer_options, {.max_queue_bytes = queue_mb << 20});
      // A launch profile may point it into the run's output folder before anything else made it.
      if (const auto parent = std::filesystem::path(out).parent_path(); !parent.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(parent, ec);
      }
      writer.open(out);
      // The recorder always subscribes with the lossless (KEEP_ALL) reader profiles: with a live
      // chain it then loses a sample only when it falls behind the writer's whole history, and
      // never holds a live writer back (those keep the last samples). --mode names the chain's
      // mode, stored in the channel metadata for replay.
      dds::DdsOptions reader_options = node.dds;
      reader_options.mode = dds::DeliveryMode::Lossless;
      dds::Participant participant(reader_options);
      std::vector<std::unique_ptr<TopicRecorder>> recorders;
      for (const auto& spec : chosen) {
        recorders.push_back(record::with_topic_type(spec.topic, [&]<class P>() -> std::unique_ptr<TopicRecorder> {
          return std::make_unique<TypedRecorder<P>>(participant, spec, idl_dir, node.dds.mode, writer,
                                                    with_foxglove ? &foxglove_options : nullptr);
        }));
      }
      std::string command_line;
      for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
      writer.add_metadata({"uavmot_record",
                           {{"command_line", command_line},
                            {"domain", std::to_string(node.dds.domain_id)},
                            {"mode", dds::to_string(node.dds.mode)}}});
      std::string names;
      for (const auto& r : recorders) names += (names.empty() ? "" : ", ") + r->topic();
      spdlog::info("recording {} to {} ({}, {})", names, out, compression, dds::to_string(node.dds.mode));

      const auto start = std::chrono::steady_clock::now();
      while (!shutdown_requested()) {
        size_t taken = 0;
        for (auto& r : recorders) taken += r->drain();
        if (duration_s > 0 && std::chrono::steady_clock::now() - start > std::chrono::duration<double>(duration_s)) break;
        if (taken == 0) recorders.front()->wait_for_data(std::chrono::milliseconds(2));
      }
      for (auto& r : recorders) {
        r->drain();
        spdlog::info("{}: {} samples{}", r->topic(), r->recorded(), r->coverage());
      }
      recorders.clear();  // no more samples: the readers go before the file closes
      writer.close();
      const auto stats = writer.statistics();
      spdlog::info("wrote {}: {} messages, {} dropped, queue peak {:.1f} MiB", out, stats.message_count, writer.dropped(),
                   static_cast<double>(writer.max_queued_bytes()) / (1 << 20));
      return kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::record_main(argc, argv); }
