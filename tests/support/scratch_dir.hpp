#pragma once
// Where tests and fuzz targets put the files they write: one folder per process under the temp
// directory (its pid keeps parallel runs, e.g. a Release and an ASan suite, apart), removed when the
// process exits normally, so a test run leaves nothing in /tmp. After a crash it stays, to look at.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace uavmot::test_support {

class ProcessScratch {
 public:
  ProcessScratch()
      : owner_(::getpid()),
        path_(std::filesystem::temp_directory_path() / ("uavmot_test_" + std::to_string(owner_))) {
    std::filesystem::create_directories(path_);
  }
  ~ProcessScratch() {
    if (::getpid() != owner_) return;  // a forked child exiting must not take its parent's files
    std::error_code ignored;           // nothing to do about a folder that cannot be removed at exit
    std::filesystem::remove_all(path_, ignored);
  }
  ProcessScratch(const ProcessScratch&) = delete;
  ProcessScratch& operator=(const ProcessScratch&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  pid_t owner_;
  std::filesystem::path path_;
};

// This process's scratch folder, created on first use.
inline const std::filesystem::path& scratch_root() {
  static const ProcessScratch scratch;
  return scratch.path();
}

// `name` inside it (a file or folder name; nothing is created).
inline std::filesystem::path scratch_path(const std::string& name) { return scratch_root() / name; }

// An empty folder `name` inside it (emptied if an earlier test of this process left it).
inline std::filesystem::path fresh_scratch_dir(const std::string& name) {
  const std::filesystem::path dir = scratch_path(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace uavmot::test_support
