#pragma once
// Starting real uavmot processes from integration tests: argv, extra environment, output to a
// log file, wait with a deadline, signal. The destructor kills a process still running.

#include <sys/types.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace uavmot::testing {

class ChildProcess {
 public:
  ChildProcess(std::vector<std::string> argv, std::string log_file, std::map<std::string, std::string> env = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Exit code (or 128 + signal), or nullopt if still running at the deadline.
  std::optional<int> wait(std::chrono::milliseconds timeout);
  void signal(int signum);
  pid_t pid() const { return pid_; }
  std::string log() const;  // what the process printed so far

 private:
  pid_t pid_ = -1;
  std::string log_file_;
  std::optional<int> exit_code_;
};

// build/bin/<name>
std::string binary(const std::string& name);
std::string read_file(const std::string& path);
// A fresh empty folder under the build tree's test output.
std::string fresh_dir(const std::string& name);

}  // namespace uavmot::testing
