#include "uavmot/source/frame_prefetcher.hpp"

#include <pthread.h>

#include <algorithm>

namespace uavmot::source {

FramePrefetcher::FramePrefetcher(std::unique_ptr<FrameSource> source, size_t depth,
                                 std::function<bool(int64_t index)> skip_undecoded)
    : source_(std::move(source)), depth_(std::max<size_t>(depth, 1)), skip_undecoded_(std::move(skip_undecoded)) {
  thread_ = std::thread([this] { run(); });
}

FramePrefetcher::~FramePrefetcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FramePrefetcher::run() {
  pthread_setname_np(pthread_self(), "uavmot-decode");  // for top -H and perf
  int64_t next_index = 1;
  try {
    while (true) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return stop_ || queue_.size() < depth_; });
        if (stop_) break;
      }
      if (skip_undecoded_ && skip_undecoded_(next_index)) {
        if (!source_->skip()) break;
        last_index_ = next_index++;
        ++skipped_;
        continue;
      }
      Frame frame;
      const bool more = source_->next(frame);
      corrupt_ = source_->skipped();
      if (!more) break;
      last_index_ = frame.index;
      next_index = frame.index + 1;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.push_back(std::move(frame));
      }
      changed_.notify_all();
    }
  } catch (...) {
    corrupt_ = source_->skipped();
    std::lock_guard<std::mutex> lock(mutex_);
    failure_ = std::current_exception();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  changed_.notify_all();
}

bool FramePrefetcher::next(Frame& frame) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return !queue_.empty() || done_; });
  if (!queue_.empty()) {
    frame = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    changed_.notify_all();
    return true;
  }
  if (failure_) {
    auto failure = failure_;
    failure_ = nullptr;
    std::rethrow_exception(failure);
  }
  return false;
}


bool FramePrefetcher::next_ready() {
  std::lock_guard<std::mutex> lock(mutex_);
  return !queue_.empty();
}

}  // namespace uavmot::source
