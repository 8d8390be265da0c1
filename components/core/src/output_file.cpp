#include "uavmot/core/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "uavmot/core/error.hpp"

namespace uavmot {

OutputFile::OutputFile(std::string path) : path_(std::move(path)) { open_fd(O_TRUNC); }

OutputFile::OutputFile(std::string path, uint64_t keep_bytes) : path_(std::move(path)) {
  open_fd(0);
  if (::ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0 || ::lseek(fd_, 0, SEEK_END) != static_cast<off_t>(keep_bytes)) {
    fail("cannot continue", errno);
  }
  bytes_ = keep_bytes;
}

void OutputFile::open_fd(int flags) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | flags, 0644);
  if (fd_ < 0) {
    // A full or failing disk is the run's failure; anything else (no such folder, no permission)
    // is a bad output path.
    const int error = errno;
    if (error == ENOSPC || error == EDQUOT || error == EIO) fail("cannot write", error);
    throw InputError("cannot write '" + path_ + "': " + std::strerror(error));
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);  // the run already failed, or close() reports for the caller
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)), bytes_(other.bytes_) {}

OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    bytes_ = other.bytes_;
  }
  return *this;
}

void OutputFile::append(std::string_view record) {
  if (fd_ < 0) throw std::logic_error("OutputFile::append on a closed file");
  size_t done = 0;
  while (done < record.size()) {
    const ssize_t n = ::write(fd_, record.data() + done, record.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;  // write(2) returning 0 for a regular file: no room
      // Cut the partial record: truncating frees space, so this works on a full disk too.
      // (Devices such as /dev/full cannot be truncated; they hold no partial line either.)
      if (done > 0 && ::ftruncate(fd_, static_cast<off_t>(bytes_)) == 0) ::lseek(fd_, static_cast<off_t>(bytes_), SEEK_SET);
      fail("cannot write", error);
    }
    done += static_cast<size_t>(n);
  }
  bytes_ += record.size();
}

void OutputFile::close() {
  if (fd_ < 0) return;
  // EINTR: Linux has closed the descriptor anyway; nothing to retry.
  if (::close(std::exchange(fd_, -1)) != 0 && errno != EINTR) fail("cannot save", errno);
}

void OutputFile::fail(const std::string& what, int error) {
  throw OutputError(what + " '" + path_ + "': " + std::strerror(error));
}

void write_output_file(const std::string& path, std::string_view content) {
  OutputFile file(path);
  file.append(content);
  file.close();
}

}  // namespace uavmot
