// uavmot-replay: republishes an MCAP recording of uavmot topics, with its original timing or
// losslessly as fast as the subscribers take it (docs/record.md). `--info` describes the file.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <thread>

#include <spdlog/spdlog.h>

#include "uavmot/core/app.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"
#include "uavmot/dds/node_options.hpp"
#include "uavmot/mcap/reader.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/record/topic_catalog.hpp"
#include "uavmot/record/typed_topic.hpp"
#include "uavmot/replay/recording_info.hpp"

namespace uavmot {
namespace {

// One replayed topic: decodes recorded CDR into the typed sample and publishes it.
class TopicPublisher {
 public:
  virtual ~TopicPublisher() = default;
  // False when a lossless write could not be delivered (no progress, or shutdown).
  virtual bool publish(const mcap::MessageView& m) = 0;
  virtual bool wait_for_readers(int count, std::chrono::milliseconds timeout) = 0;
  virtual bool flush() = 0;
  uint64_t published() const { return published_; }

 protected:
  uint64_t published_ = 0;
};

template <class PubSubType>
class TypedPublisher final : public TopicPublisher {
 public:
  TypedPublisher(dds::Participant& participant, const record::TopicSpec& spec, int required_readers, bool lossless)
      : writer_(participant.make_writer<PubSubType>(spec.topic, spec.topic_class)), lossless_(lossless) {
    if (lossless_) writer_->set_required_readers(required_readers);
  }

  bool publish(const mcap::MessageView& m) override {
    dds::from_cdr(type_, m.data, m.size, sample_,
                     fmt::format("{}: message {} of {} (chunk at byte offset {})", m.channel->topic, m.sequence,
                                 m.channel->topic, m.source_offset));
    const bool ok = lossless_ ? writer_->write_reliably(sample_) : writer_->write(sample_);
    if (ok) ++published_;
    return ok || !lossless_;
  }
  bool wait_for_readers(int count, std::chrono::milliseconds timeout) override {
    return writer_->wait_for_matched(count, timeout);
  }
  bool flush() override { return writer_->flush(std::chrono::seconds(30)); }

 private:
  std::unique_ptr<dds::TopicWriter<PubSubType>> writer_;
  bool lossless_;
  PubSubType type_;
  typename PubSubType::type sample_;
};

// Sleeps until `target`, waking every 100 ms to notice a shutdown request.
void sleep_until(std::chrono::steady_clock::time_point target) {
  while (!shutdown_requested()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= target) return;
    std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(target - now, std::chrono::milliseconds(100)));
  }
}

std::map<std::string, int> parse_topic_counts(const std::vector<std::string>& entries) {
  std::map<std::string, int> out;
  for (const auto& e : entries) {
    const auto eq = e.find('=');
    int n = -1;
    try {
      if (eq != std::string::npos) n = std::stoi(e.substr(eq + 1));
    } catch (const std::exception&) {
      n = -1;
    }
    if (eq == std::string::npos || eq == 0 || n < 0) {
      throw InvalidArgument("--topic-subscribers expects TOPIC=N, got '" + e + "'");
    }
    out[e.substr(0, eq)] = n;
  }
  return out;
}

int replay_main(int argc, char** argv) {
  dds::NodeOptions node;
  std::string file;
  bool info_only = false, loop = false, lossless = false;
  double rate = 1.0, start_offset_s = 0.0, duration_s = 0.0;
  std::vector<std::string> topics, exclude, topic_subscribers;
  return run_app(argc, argv, "replay", "republish an MCAP recording of uavmot topics", [&](CLI::App& app) {
    app.add_option("file", file, "the recording (.mcap)")->required();
    app.add_flag("--info", info_only, "print what the recording holds (topics, types, counts, duration) and exit");
    app.add_option("--topics", topics, "topics or wildcard patterns to replay (default: every recorded uavmot topic)");
    app.add_option("--exclude", exclude, "topics or wildcard patterns not to replay");
    app.add_option("--rate", rate, "playback speed factor on the recorded timing")->check(uavmot::positive_finite())->capture_default_str();
    app.add_flag("--loop", loop, "start over at the end");
    app.add_option("--start-offset", start_offset_s, "skip this many seconds from the start")->check(uavmot::non_negative_finite());
    app.add_option("--duration", duration_s, "replay only this many seconds (from the start offset)")->check(uavmot::positive_finite());
    app.add_flag("--lossless", lossless,
                 "ignore the timing: publish as fast as the subscribers take it, nothing dropped (with --wait-subscribers)");
    app.add_option("--topic-subscribers", topic_subscribers,
                   "TOPIC=N: wait for N readers of this topic (overrides --wait-subscribers for it)");
    dds::add_node_options(app, node);
    return [&]() -> int {
      dds::finalize(node, "replay");
      mcap::Reader reader;
      reader.open(file);
      if (info_only) {
        std::fputs(replay::recording_info(reader).c_str(), stdout);
        return reader.damage() ? kExitFailure : kExitOk;
      }
      if (reader.damage()) spdlog::warn("{}; replaying what precedes the damage", reader.damage()->description);
      install_shutdown_handler();

      // The channels to replay, with their uavmot topic.
      std::vector<std::pair<const mcap::Channel*, const record::TopicSpec*>> chosen;
      for (const auto& [id, channel] : reader.channels()) {
        if (!record::is_selected(channel.topic, topics, exclude)) continue;
        const auto* spec = record::find_topic(channel.topic);
        if (!spec || channel.message_encoding != "cdr") {
          spdlog::warn("{}: not a uavmot topic in CDR ({}); not replayed", channel.topic, channel.message_encoding);
          continue;
        }
        const auto schema = reader.schemas().find(channel.schema_id);
        if (schema != reader.schemas().end() && schema->second.name != spec->type_name) {
          throw InputError(file + ": channel " + channel.topic + " has type " + schema->second.name + ", uavmot expects " +
                           spec->type_name);
        }
        chosen.emplace_back(&channel, spec);
      }
      if (chosen.empty()) throw InputError(file + ": no recorded topic matches --topics/--exclude");

      // QoS: --lossless or --mode override; else the mode the recording was made in.
      const bool mode_given = app.get_option("--mode")->count() > 0;
      if (lossless) {
        node.dds.mode = dds::DeliveryMode::Lossless;
      } else if (!mode_given) {
        node.dds.mode = record::recorded_mode(*chosen.front().first, dds::DeliveryMode::Lossless);
      }
      const auto per_topic = parse_topic_counts(topic_subscribers);
      dds::Participant participant(node.dds);
      std::map<uint16_t, std::unique_ptr<TopicPublisher>> publishers;
      mcap::ReadFilter filter;
      for (const auto& [channel, spec] : chosen) {
        const auto n = per_topic.find(spec->topic);
        const int required = n == per_topic.end() ? node.wait_subscribers : n->second;
        publishers[channel->id] = record::with_topic_type(spec->topic, [&]<class P>() -> std::unique_ptr<TopicPublisher> {
          return std::make_unique<TypedPublisher<P>>(participant, *spec, required, lossless);
        });
        filter.topics.insert(spec->topic);
        if (required > 0 && !publishers[channel->id]->wait_for_readers(required, std::chrono::seconds(60))) {
          if (shutdown_requested()) return kExitOk;
          spdlog::error("{}: fewer than {} readers after 60 s", spec->topic, required);
          return kExitFailure;
        }
      }
      const auto& stats = reader.statistics();
      filter.start_time = stats.message_start_time + static_cast<uint64_t>(std::llround(start_offset_s * 1e9));
      if (duration_s > 0) filter.end_time = filter.start_time + static_cast<uint64_t>(std::llround(duration_s * 1e9));
      spdlog::info("replaying {} topic(s) of {} ({}, {})", chosen.size(), file, dds::to_string(node.dds.mode),
                   lossless ? "as fast as the subscribers take it" : fmt::format("rate {}", rate));

      uint64_t replayed = 0;
      bool damaged = false, failed = false;
      do {
        auto cursor = reader.messages(filter);
        const auto start = std::chrono::steady_clock::now();
        bool first = true;
        uint64_t first_log_time = 0;
        mcap::MessageView m;
        while (!shutdown_requested()) {
          try {
            if (!cursor.next(m)) break;
          } catch (const InputError& e) {
            spdlog::error("{}", e.what());
            damaged = true;
            break;
          }
          if (!lossless) {
            if (first) first_log_time = m.log_time;
            first = false;
            const double offset_s = static_cast<double>(m.log_time - first_log_time) / 1e9 / rate;
            sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(offset_s)));
          }
          if (!publishers.at(m.channel->id)->publish(m)) {
            failed = true;
            break;
          }
          ++replayed;
        }
      } while (loop && !shutdown_requested() && !damaged && !failed);
      for (auto& [id, p] : publishers) p->flush();
      for (const auto& [channel, spec] : chosen) {
        spdlog::info("{}: {} messages", channel->topic, publishers.at(channel->id)->published());
      }
      std::printf("replayed %llu messages\n", static_cast<unsigned long long>(replayed));
      std::fflush(stdout);
      return damaged || failed ? kExitFailure : kExitOk;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::replay_main(argc, argv); }
