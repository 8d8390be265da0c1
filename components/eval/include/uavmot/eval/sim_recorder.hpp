#pragma once
// Collects the simulator's ground truth in memory so tests can score a run without files:
//
//   sim::Simulator sim(scenario, seed);
//   eval::SimRecorder truth(sim);
//   eval::Predictions predictions;
//   sim::SimFrame frame;
//   while (sim.next(frame)) {
//     truth.add(frame);
//     predictions.add_tracks(tracker.process(...));
//   }
//   auto result = eval::evaluate(truth.sequence(), predictions);

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "uavmot/eval/sequence.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::eval {

class SimRecorder {
 public:
  explicit SimRecorder(const sim::Simulator& simulator, bool keep_masks = true);
  void add(const sim::SimFrame& frame);
  const Sequence& sequence() const { return sequence_; }

 private:
  Sequence sequence_;
  bool keep_masks_;
  // Id masks as 16-bit PNG bytes: small enough to keep a whole sequence.
  std::shared_ptr<std::map<int64_t, std::vector<uint8_t>>> masks_;
};

}  // namespace uavmot::eval
