#include "uavmot/mcap/queued_writer.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

QueuedWriter::QueuedWriter(WriterOptions writer_options, QueuedWriterOptions options)
    : writer_(std::move(writer_options)), options_(options) {
  if (options_.max_queue_bytes == 0) throw InvalidArgument("mcap::QueuedWriterOptions::max_queue_bytes must be > 0");
}

QueuedWriter::~QueuedWriter() {
  if (thread_.joinable()) {
    try {
      close();
    } catch (...) {
      // A destructor cannot report; the .tmp file stays for recover().
    }
  }
}

void QueuedWriter::open(const std::string& path) {
  if (thread_.joinable()) throw InvalidArgument("mcap::QueuedWriter::open: already open");
  {
    std::lock_guard<std::mutex> lock(writer_mutex_);
    writer_.open(path);
  }
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.clear();
    queued_bytes_ = max_queued_bytes_ = dropped_ = 0;
    stopping_ = false;
    failure_ = nullptr;
  }
  channels_.clear();
  thread_ = std::thread([this] { run(); });
}

uint16_t QueuedWriter::add_schema(const std::string& name, const std::string& encoding, std::string_view data) {
  std::lock_guard<std::mutex> lock(writer_mutex_);
  return writer_.add_schema(name, encoding, data);
}

uint16_t QueuedWriter::add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                   const KeyValueMap& metadata) {
  uint16_t id;
  {
    std::lock_guard<std::mutex> lock(writer_mutex_);
    id = writer_.add_channel(schema_id, topic, message_encoding, metadata);
  }
  std::lock_guard<std::mutex> lock(queue_mutex_);
  channels_.insert(id);
  return id;
}

void QueuedWriter::add_metadata(const Metadata& metadata) {
  std::lock_guard<std::mutex> lock(writer_mutex_);
  writer_.add_metadata(metadata);
}

bool QueuedWriter::write(uint16_t channel_id, uint32_t sequence, uint64_t log_time_ns, uint64_t publish_time_ns,
                         std::vector<uint8_t> data, bool wait_when_full) {
  std::unique_lock<std::mutex> lock(queue_mutex_);
  if (!thread_.joinable() || stopping_) throw InvalidArgument("mcap::QueuedWriter::write: not open");
  if (!channels_.count(channel_id)) {
    throw InvalidArgument(fmt::format("mcap::QueuedWriter::write: unknown channel id {}", channel_id));
  }
  // A message larger than the whole queue is still accepted once the queue is empty.
  const auto fits = [&] { return queued_bytes_ == 0 || queued_bytes_ + data.size() <= options_.max_queue_bytes; };
  if (!fits() || failure_) {
    if (!wait_when_full && !failure_) {
      ++dropped_;
      return false;
    }
    queue_changed_.wait(lock, [&] { return fits() || failure_; });
  }
  if (failure_) std::rethrow_exception(failure_);
  queued_bytes_ += data.size();
  max_queued_bytes_ = std::max(max_queued_bytes_, queued_bytes_);
  queue_.push_back(Item{channel_id, sequence, log_time_ns, publish_time_ns, std::move(data)});
  queue_changed_.notify_all();
  return true;
}

void QueuedWriter::run() {
  for (;;) {
    Item item;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      queue_changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
      if (queue_.empty()) return;  // stopping and drained
      item = std::move(queue_.front());
      queue_.pop_front();
    }
    try {
      std::lock_guard<std::mutex> lock(writer_mutex_);
      writer_.write(item.channel, item.sequence, item.log_time, item.publish_time, item.data.data(), item.data.size());
    } catch (...) {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      failure_ = std::current_exception();
      queue_.clear();
      queued_bytes_ = 0;
      queue_changed_.notify_all();
      return;
    }
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queued_bytes_ -= item.data.size();
    queue_changed_.notify_all();
  }
}

void QueuedWriter::close() {
  if (!thread_.joinable()) throw InvalidArgument("mcap::QueuedWriter::close: not open");
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
    queue_changed_.notify_all();
  }
  thread_.join();
  std::exception_ptr failure;
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    failure = failure_;
  }
  if (failure) {
    std::rethrow_exception(failure);  // the .tmp file stays: every complete chunk is recoverable
  }
  std::lock_guard<std::mutex> lock(writer_mutex_);
  writer_.close();
}

uint64_t QueuedWriter::dropped() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return dropped_;
}

uint64_t QueuedWriter::queued_bytes() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return queued_bytes_;
}

uint64_t QueuedWriter::max_queued_bytes() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return max_queued_bytes_;
}

Statistics QueuedWriter::statistics() const {
  std::lock_guard<std::mutex> lock(writer_mutex_);
  return writer_.statistics();
}

}  // namespace uavmot::mcap
