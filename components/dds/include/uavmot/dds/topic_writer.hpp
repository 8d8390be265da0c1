#pragma once
// A typed DataWriter whose every write() result is checked.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <spdlog/spdlog.h>

#include "uavmot/core/shutdown.hpp"

namespace uavmot::dds {

// A lossless writer whose readers had not all matched when its first sample had waited
// kFirstSampleReaderPatience for them. The process cannot do its job, and a new participant is the remedy: with DDS Security
// on Fast DDS 2.9, 4 of 28 secure starts of the air chain left one pair of its endpoints unmatched
// for good (docs/deployment.md, "Endpoints that never match"). The component exits 1
// (core/app.cpp), so the launcher respawns it; the respawned process is discovered afresh.
class ReadersNeverMatched : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How long a lossless sample waits for its readers (to match, then to acknowledge) before it is
// given up, and, shorter, how long the first sample of a writer with exit_if_readers_never_match()
// waits before its process exits. The first must exceed the second plus a respawn: a writer whose
// reader restarts itself must still be waiting when the new reader is there, or two processes give
// up at once and the frames in work between them are lost (seen: source and motion both at 60 s).
inline constexpr std::chrono::seconds kReaderPatience{180};
inline constexpr std::chrono::seconds kFirstSampleReaderPatience{60};

template <class PubSubType>
class TopicWriter {
 public:
  using Sample = typename PubSubType::type;

  TopicWriter(eprosima::fastdds::dds::DataWriter* writer, std::string topic) : writer_(writer), topic_(std::move(topic)) {}

  // Best-effort publish (live mode): returns false, and logs, if the middleware refused the sample.
  bool write(Sample& sample) {
    if (writer_->write(&sample)) {
      count_sent(sample);
      return true;
    }
    spdlog::warn("{}: write() refused a sample", topic_);
    return false;
  }

  // Lossless publish. First waits until every matched reader acknowledged the previous sample,
  // then writes this one; flush() waits for the last. Readers keep bounded queues, so a slow reader
  // holds the writer back here instead of losing data, and the wait for the previous sample overlaps
  // with whatever the caller did since (e.g. decoding the next frame).
  // Returns false only when `timeout` passes without progress or shutdown is requested; throws
  // ReadersNeverMatched when exit_if_readers_never_match() was called and the first sample waited
  // kFirstSampleReaderPatience (or `timeout`, if shorter) for its readers.
  bool write_reliably(Sample& sample, std::chrono::milliseconds timeout = kReaderPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    if (matched() < required_readers_) {
      // A reader is (re)starting: publishing now would lose this sample for it.
      spdlog::info("{}: waiting for {} reader(s), {} matched", topic_, required_readers_, matched());
      const bool first_sample_rule = exit_if_never_matched_ && samples_sent_ == 0;
      const auto wait = first_sample_rule ? std::min<std::chrono::milliseconds>(timeout, kFirstSampleReaderPatience) : timeout;
      if (!wait_for_matched(required_readers_, wait)) {
        if (first_sample_rule && !shutdown_requested()) {
          throw ReadersNeverMatched(topic_ + ": only " + std::to_string(matched()) + " of " + std::to_string(required_readers_) +
                                    " readers matched in the " + std::to_string(wait.count()) +
                                    " ms before the first sample; exiting, so that a restarted process is discovered afresh");
        }
        spdlog::error("{}: fewer than {} readers for {} ms", topic_, required_readers_, timeout.count());
        return false;
      }
      spdlog::info("{}: {} reader(s) matched, going on", topic_, matched());
    }
    if (!flush(timeout)) return false;
    while (!writer_->write(&sample)) {
      if (std::chrono::steady_clock::now() > deadline || shutdown_requested()) {
        spdlog::error("{}: write() kept failing for {} ms", topic_, timeout.count());
        return false;
      }
      writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(0, 100000000));
      waiting();
    }
    count_sent(sample);
    return true;
  }

  // Waits until every matched reader acknowledged everything written; false on timeout or shutdown.
  bool flush(std::chrono::milliseconds timeout = std::chrono::seconds(30)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(0, 100000000)) !=
           eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (matched() == 0) return true;  // the readers left; nobody to wait for
      waiting();
      if (std::chrono::steady_clock::now() > deadline || shutdown_requested()) {
        spdlog::error("{}: samples not acknowledged by every reader within {} ms", topic_, timeout.count());
        return false;
      }
    }
    return true;
  }

  // Lossless publishing waits until at least this many readers are matched (at the start, and again
  // whenever a reader leaves, e.g. a component being respawned).
  void set_required_readers(int count) { required_readers_ = count; }

  // For a writer whose readers are processes started beside it (the chain under one launcher), so
  // that their absence after the timeout is a fault, not a late start: then the first sample's
  // wait throws ReadersNeverMatched instead of giving that sample up. (Not the downlink: its
  // ground reader may come much later.)
  void exit_if_readers_never_match() { exit_if_never_matched_ = true; }

  int matched() const {
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }

  // Waits until at least `count` readers matched; false on timeout or shutdown.
  bool wait_for_matched(int count, std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (matched() < count) {
      if (std::chrono::steady_clock::now() > deadline || shutdown_requested()) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      waiting();
    }
    return true;
  }

  // Called about every 100 ms while a call above waits for readers (HealthReporter::watch installs
  // its tick): a component held back by a slow or stopped reader keeps reporting, so the launcher's
  // watchdog tells it from a component that hangs itself (docs/launch.md).
  void set_while_waiting(std::function<void()> f) { while_waiting_ = std::move(f); }

  uint64_t samples_sent() const { return samples_sent_; }
  uint64_t bytes_sent() const { return bytes_sent_; }
  const std::string& topic() const { return topic_; }
  eprosima::fastdds::dds::DataWriter* native() const { return writer_; }

 private:
  void count_sent(Sample& sample) {
    ++samples_sent_;
    bytes_sent_ += type_.getSerializedSizeProvider(&sample)();
  }

  void waiting() const {
    if (while_waiting_) while_waiting_();
  }

  eprosima::fastdds::dds::DataWriter* writer_;
  std::string topic_;
  std::function<void()> while_waiting_;
  PubSubType type_;
  int required_readers_ = 0;
  bool exit_if_never_matched_ = false;
  uint64_t samples_sent_ = 0;
  uint64_t bytes_sent_ = 0;
};

}  // namespace uavmot::dds
