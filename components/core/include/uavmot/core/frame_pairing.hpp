#pragma once
// Joins two inputs of one stream by frame index and releases the pairs strictly in frame order,
// which is how the distributed chain stays identical to the in-process one: segmentation needs
// frame k with motion k, tracking needs motion k with segmentation k.
//
// Each side comes from one writer, in frame order. So once a newer index is complete, an older
// incomplete one can never complete (its sample was lost: live-mode drops, or a producer that
// crashed and was respawned); it is dropped and counted instead of blocking the stream forever.
// In an undisturbed lossless run every index completes and pairs come out 1, 2, 3, ...

#include <cstdint>
#include <map>
#include <optional>
#include <utility>

namespace uavmot {

template <class A, class B>
class FramePairing {
 public:
  struct Pair {
    int64_t index;
    A first;
    B second;
  };


  void add_first(int64_t index, A value) { pending_[index].first = std::move(value); }
  void add_second(int64_t index, B value) { pending_[index].second = std::move(value); }

  // The next pair in frame order, if it is complete.
  std::optional<Pair> pop() {
    // Drop everything older than the oldest complete index.
    auto complete = pending_.begin();
    while (complete != pending_.end() && !(complete->second.first && complete->second.second)) ++complete;
    if (complete == pending_.end()) return std::nullopt;
    while (pending_.begin() != complete) {
      pending_.erase(pending_.begin());
      ++dropped_;
    }
    auto& [index, slots] = *pending_.begin();
    if (!slots.first || !slots.second) return std::nullopt;
    Pair pair{index, std::move(*slots.first), std::move(*slots.second)};
    pending_.erase(pending_.begin());
    return pair;
  }

  size_t pending() const { return pending_.size(); }
  uint64_t dropped() const { return dropped_; }

 private:
  struct Slots {
    std::optional<A> first;
    std::optional<B> second;
  };
  std::map<int64_t, Slots> pending_;
  uint64_t dropped_ = 0;
};

}  // namespace uavmot
