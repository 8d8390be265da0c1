#include "uavmot/core/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "uavmot/core/error.hpp"

namespace uavmot {
namespace {

[[noreturn]] void fail(const std::string& what, const std::string& file, int error) {
  throw OutputError(what + " '" + file + "': " + std::strerror(error));
}

}  // namespace

void write_file_durably(const std::string& path, const std::vector<uint8_t>& bytes) {
  // Synced before and after the rename, so a host that loses power keeps either the previous
  // content or this one (docs/launch.md: the saved states outlive the host).
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create", tmp, errno);
  for (size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;  // write(2) returning 0 for a regular file: no room
      ::close(fd);
      fail("cannot write", tmp, error);
    }
    done += static_cast<size_t>(n);
  }
  if (::fdatasync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    fail("cannot sync", tmp, error);
  }
  if (::close(fd) != 0 && errno != EINTR) fail("cannot save", tmp, errno);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot rename '" + tmp + "' to", path, errno);
  // The rename is done; a folder that cannot be opened or synced (some file systems refuse) leaves
  // it to the next sync of the system.
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const int dir_fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

}  // namespace uavmot
