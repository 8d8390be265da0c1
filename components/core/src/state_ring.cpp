#include "uavmot/core/state_ring.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "uavmot/core/durable_file.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot {
namespace fs = std::filesystem;
namespace {

// The frame in NAME when it is PREFIX + digits + SUFFIX.
std::optional<int64_t> frame_in_name(const std::string& name, const std::string& prefix, const std::string& suffix) {
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 18) return std::nullopt;
  for (char c : digits) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  }
  return std::stoll(digits);
}

std::string frame_range(const std::vector<int64_t>& frames) {
  return frames.size() == 1 ? std::to_string(frames.front())
                            : std::to_string(frames.front()) + "-" + std::to_string(frames.back());
}

// Makes removals in DIR durable (a folder that cannot be synced leaves it to the system, as
// write_file_durably does).
void sync_folder(const std::string& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::optional<std::vector<uint8_t>> load_state_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(what + " file '" + path + "' cannot be opened");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(what + " file '" + path + "' cannot be read");
  return bytes;
}

StateRing::StateRing(std::string dir, std::string kind, std::string stream, int keep)
    : dir_(std::move(dir)), kind_(std::move(kind)), stream_(std::move(stream)), keep_(keep > 0 ? static_cast<size_t>(keep) : 0) {
  if (keep < 1) throw InvalidArgument(fmt::format("{}s to keep per stream: {} (at least 1)", what(), keep));
  std::error_code ec;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (auto frame = frame_in_name(name, prefix(), ".bin"); frame && fs::path(path(*frame)).filename() == name) {
      frames_.insert(*frame);  // only names as this ring writes them, which it can also remove
    } else if (frame_in_name(name, prefix(), ".bin.tmp")) {
      fs::remove(it->path(), ec);  // a write a crash cut short; the state before it is kept
      ec.clear();
    }
  }
}

std::string StateRing::prefix() const { return kind_ + "_" + stream_ + "."; }

std::string StateRing::what() const {
  std::string words = kind_;
  std::replace(words.begin(), words.end(), '_', ' ');
  return words;
}

std::string StateRing::path(int64_t frame) const { return fmt::format("{}/{}{:010d}.bin", dir_, prefix(), frame); }

std::string StateRing::legacy_path() const { return dir_ + "/" + kind_ + "_" + stream_ + ".bin"; }

void StateRing::save(int64_t frame, const std::vector<uint8_t>& bytes) {
  write_file_durably(path(frame), bytes);
  frames_.insert(frame);
  std::error_code ec;
  bool removed_later = false;
  while (*frames_.rbegin() != frame) {
    fs::remove(path(*frames_.rbegin()), ec);
    frames_.erase(std::prev(frames_.end()));
    removed_later = true;
  }
  // A later state that came back after a power loss would be restored by the next launch.
  if (removed_later) sync_folder(dir_);
  // Older states removed without a sync: one that comes back is only removed again.
  while (frames_.size() > keep_) {
    fs::remove(path(*frames_.begin()), ec);
    frames_.erase(frames_.begin());
  }
}

std::optional<int64_t> StateRing::adopt_legacy(const std::function<int64_t(const std::vector<uint8_t>&)>& frame_of) {
  const auto bytes = load_state_file(legacy_path(), what());
  if (!bytes) return std::nullopt;
  int64_t frame = 0;
  try {
    frame = frame_of(*bytes);
  } catch (const InputError& e) {
    throw InputError(what() + " file '" + legacy_path() + "': " + e.what() + " (remove it to start this stream afresh)");
  }
  // Written as the ring's without removing later states: they may be the ones a new launch needs.
  write_file_durably(path(frame), *bytes);
  frames_.insert(frame);
  fs::remove(legacy_path());
  sync_folder(dir_);
  return frame;
}

RestoreChoice restore_before(const StateRing& ring, int64_t first_frame,
                             const std::function<int64_t(const std::vector<uint8_t>&)>& restore) {
  RestoreChoice choice;
  const auto& frames = ring.frames();
  for (auto it = frames.upper_bound(first_frame - 1); it != frames.end(); ++it) choice.newer.push_back(*it);
  for (auto it = std::make_reverse_iterator(frames.upper_bound(first_frame - 1)); it != frames.rend(); ++it) {
    const std::string file = ring.path(*it);
    try {
      const auto bytes = load_state_file(file, ring.what());
      if (!bytes) throw InputError("removed while this process started");
      const int64_t held = restore(*bytes);
      if (held != *it) throw InputError(fmt::format("holds frame {}, not the frame its name says", held));
      choice.restored = *it;
      return choice;
    } catch (const InputError& e) {
      choice.refused.push_back("'" + file + "': " + e.what());
    }
  }
  if (!choice.refused.empty()) {
    std::string all;
    for (const auto& r : choice.refused) all += (all.empty() ? "" : "; ") + r;
    throw InputError("no usable " + ring.what() + " before frame " + std::to_string(first_frame) + ": " + all +
                     " (remove them to start this stream afresh)");
  }
  return choice;
}

std::optional<int64_t> restore_and_report(const StateRing& ring, const std::string& stream, int64_t first_frame,
                                          const std::function<int64_t(const std::vector<uint8_t>&)>& restore) {
  size_t bytes_restored = 0;
  const auto choice = restore_before(ring, first_frame, [&](const std::vector<uint8_t>& bytes) {
    const int64_t frame = restore(bytes);
    bytes_restored = bytes.size();
    return frame;
  });
  const std::string what = ring.what();
  for (const auto& refused : choice.refused) {
    spdlog::warn("stream '{}': passed over a damaged {} for an older one: {}", stream, what, refused);
  }
  if (choice.restored) {
    spdlog::info("stream '{}': restored the {} at frame {} ({} bytes): the newest kept before the first frame "
                 "received ({})",
                 stream, what, *choice.restored, bytes_restored, first_frame);
    if (!choice.newer.empty()) {
      spdlog::info("stream '{}': the kept states of frames {} are not used (after frame {}); they are replaced as "
                   "this run saves",
                   stream, frame_range(choice.newer), first_frame - 1);
    }
  } else if (!choice.newer.empty()) {
    spdlog::warn("stream '{}': the first frame received is {}, but every kept {} is of a later frame ({}): starting "
                 "this stream afresh (continuing from one would skip the frames up to it); they are replaced as "
                 "this run saves",
                 stream, first_frame, what, frame_range(choice.newer));
  }
  return choice.restored;
}

}  // namespace uavmot
