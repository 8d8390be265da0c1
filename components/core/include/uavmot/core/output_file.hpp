#pragma once
// A result file written in whole records: each append() is one write(2) of complete lines, and a
// write that fails (a full disk) is cut back to the last complete record before OutputError is
// thrown, so a reader never finds half a line. close() checks too (network file systems report
// there). No fsync: ext4 and tmpfs report a full disk at write(2), and a sync per file would
// stall every run on a busy disk.

#include <cstdint>
#include <string>
#include <string_view>

namespace uavmot {

class OutputFile {
 public:
  OutputFile() = default;
  // Creates or truncates PATH; throws InputError when it cannot be opened (OutputError on a full
  // or failing disk).
  explicit OutputFile(std::string path);
  // Opens PATH to continue it: keeps its first KEEP_BYTES (whole lines; the rest is cut) and
  // appends after them. Creates PATH when it does not exist and KEEP_BYTES is 0.
  OutputFile(std::string path, uint64_t keep_bytes);
  ~OutputFile();
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&& other) noexcept;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Writes RECORD (complete lines) or nothing; throws OutputError naming the file and the reason.
  void append(std::string_view record);
  // Closes; throws OutputError. Closing a closed file does nothing.
  void close();

  bool is_open() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }
  uint64_t bytes() const { return bytes_; }

 private:
  void open_fd(int flags);
  [[noreturn]] void fail(const std::string& what, int error);

  std::string path_;
  int fd_ = -1;
  uint64_t bytes_ = 0;  // complete records written
};

// Writes CONTENT to PATH as one record and closes it (summary.json).
void write_output_file(const std::string& path, std::string_view content);

}  // namespace uavmot
