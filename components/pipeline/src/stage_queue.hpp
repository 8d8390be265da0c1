#pragma once
// A bounded queue from one producer thread to one consumer thread, in order. The producer ends
// it with close(), optionally handing over its exception, which the consumer gets after the items
// before it; the consumer can cancel(), which wakes a producer blocked on a full queue.

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <utility>

namespace uavmot::pipeline {

template <typename T>
class StageQueue {
 public:
  explicit StageQueue(size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  // Blocks while full. False when the consumer cancelled: the item is dropped, stop producing.
  bool push(T item) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return cancelled_ || items_.size() < capacity_; });
    if (cancelled_) return false;
    items_.push_back(std::move(item));
    lock.unlock();
    changed_.notify_all();
    return true;
  }

  // The producer's last call: no more items; `failure` (if any) is rethrown by pop() after them.
  void close(std::exception_ptr failure = nullptr) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
      failure_ = std::move(failure);
    }
    changed_.notify_all();
  }

  // Blocks while empty. False once closed and drained; rethrows the producer's failure then.
  bool pop(T& item) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return !items_.empty() || closed_; });
    if (!items_.empty()) {
      item = std::move(items_.front());
      items_.pop_front();
      lock.unlock();
      changed_.notify_all();
      return true;
    }
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    return false;
  }

  // The consumer stops early (its own failure, a shutdown): the producer's next push returns false.
  void cancel() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      cancelled_ = true;
      items_.clear();
    }
    changed_.notify_all();
  }

 private:
  const size_t capacity_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<T> items_;
  bool closed_ = false, cancelled_ = false;
  std::exception_ptr failure_;
};

}  // namespace uavmot::pipeline
