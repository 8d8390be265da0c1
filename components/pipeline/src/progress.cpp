#include "uavmot/pipeline/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace uavmot::pipeline {

Progress::Progress(std::string label, int64_t total_frames, bool enabled)
    : label_(std::move(label)),
      total_(total_frames),
      enabled_(enabled),
      terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

void Progress::update(int64_t frames_done) {
  done_ = frames_done;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const auto since = now - last_print_;
  if (since < (terminal_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(5000))) return;
  last_print_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fps = elapsed > 0 ? static_cast<double>(done_) / elapsed : 0.0;
  char line[160];
  if (total_ > 0 && fps > 0) {
    const double eta = static_cast<double>(total_ - done_) / fps;
    std::snprintf(line, sizeof(line), "%s: frame %lld/%lld  %.1f fps  ETA %.0f s", label_.c_str(),
                  static_cast<long long>(done_), static_cast<long long>(total_), fps, eta);
  } else {
    std::snprintf(line, sizeof(line), "%s: frame %lld  %.1f fps", label_.c_str(), static_cast<long long>(done_), fps);
  }
  std::fprintf(stderr, terminal_ ? "\r%-78s" : "%s\n", line);
  std::fflush(stderr);
}

void Progress::finish() {
  if (enabled_ && terminal_) std::fprintf(stderr, "\n");
}

}  // namespace uavmot::pipeline
