#pragma once
// A stream's last N saved states of one chain stage, one file per frame:
// DIR/<kind>_<stream>.<frame, 10 digits>.bin (kind: "motion_state", "segmentation_state").
// Several, not one, because after a stop mid-stream a stage's newest state can be ahead of the
// tracker's (frames it published that the tracker never got): a new launch that starts after the
// tracker's frame K needs the stage's state at K, which only a ring that kept it still has
// (docs/launch.md, "Continuing the tracks in a new launch").

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace uavmot {

constexpr int kDefaultStatesKept = 32;

// nullopt when the file does not exist; throws InputError ("<what> file '<path>' ...") when it
// exists but cannot be read.
std::optional<std::vector<uint8_t>> load_state_file(const std::string& path, const std::string& what);

class StateRing {
 public:
  // Lists the states of STREAM already in DIR (a folder that does not exist holds none). KIND is the
  // file names' stem ("motion_state"); messages call the states "<kind with spaces>s".
  // Throws InvalidArgument when KEEP < 1.
  StateRing(std::string dir, std::string kind, std::string stream, int keep);

  // Frames whose states are kept, oldest first.
  const std::set<int64_t>& frames() const { return frames_; }
  std::string path(int64_t frame) const;
  // The single state file of earlier versions (<kind>_<stream>.bin).
  std::string legacy_path() const;
  // "motion state": what the states are called in messages.
  std::string what() const;

  // Writes FRAME's state durably (uavmot::write_file_durably), then removes the states of later
  // frames (a run this one no longer continues; removed durably, so a power loss cannot bring them
  // back) and every state but the newest `keep`. Throws OutputError when the write fails (the ring is
  // then unchanged).
  void save(int64_t frame, const std::vector<uint8_t>& bytes);

  // Turns a legacy single file into the ring's state of the frame it holds (FRAME_OF returns it, or
  // throws InputError for a file it refuses). Returns that frame, nullopt without a legacy file.
  std::optional<int64_t> adopt_legacy(const std::function<int64_t(const std::vector<uint8_t>&)>& frame_of);

 private:
  std::string prefix() const;  // <kind>_<stream>.

  std::string dir_;
  std::string kind_;
  std::string stream_;
  size_t keep_;
  std::set<int64_t> frames_;
};

// The outcome of restore_before().
struct RestoreChoice {
  std::optional<int64_t> restored;     // the frame of the state restored; nullopt: start afresh
  std::vector<std::string> refused;    // "file: reason" of the states passed over as damaged, newest first
  std::vector<int64_t> newer;          // kept states after FIRST_FRAME - 1 (not usable), oldest first
};

// Restores, with RESTORE, the newest kept state of a frame before FIRST_FRAME (FIRST_FRAME - 1
// continues exactly). RESTORE throws InputError for a state it refuses (damaged, other options) and
// otherwise returns the frame the state holds; a state that holds another frame than its file's name
// says is refused too. Refused states are passed over for the next older one. Throws InputError,
// naming every file, when there were states before FIRST_FRAME and all were refused.
RestoreChoice restore_before(const StateRing& ring, int64_t first_frame,
                             const std::function<int64_t(const std::vector<uint8_t>&)>& restore);

// restore_before() as a node does it on the first frame it receives of STREAM, saying what it did in
// the log: the states passed over as damaged (warnings), the one restored and its size, the kept
// states after it that go unused, or that every kept state is of a later frame (a warning: the
// stream starts afresh rather than skip the frames up to one). Returns the frame restored.
std::optional<int64_t> restore_and_report(const StateRing& ring, const std::string& stream, int64_t first_frame,
                                          const std::function<int64_t(const std::vector<uint8_t>&)>& restore);

}  // namespace uavmot
