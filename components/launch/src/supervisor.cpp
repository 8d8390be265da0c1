#include "uavmot/launch/supervisor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <thread>

#include "uavmot/core/error.hpp"
#include "uavmot/core/shutdown.hpp"

namespace uavmot::launch {
namespace {
using Clock = std::chrono::steady_clock;

Clock::time_point after_seconds(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

struct Child {
  const ProcessSpec* spec = nullptr;
  std::string program;
  std::vector<std::string> argv;
  pid_t pid = -1;
  int out_fd = -1;
  std::string partial_line;
  int respawns = 0;
  std::optional<Clock::time_point> respawn_at;
  Clock::time_point started_at;
  bool finished = false;
  bool hung = false;  // the watchdog killed it
};

std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exited with code " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "stopped";
}

class Runner {
 public:
  Runner(const Profile& profile, const std::vector<std::string>& programs, HealthMonitor* health) : health_(health) {
    for (size_t i = 0; i < profile.processes.size(); ++i) {
      Child c;
      c.spec = &profile.processes[i];
      c.program = programs[i];
      c.argv.push_back(c.program);
      for (const auto& a : c.spec->args) c.argv.push_back(a);
      if (c.spec->common_args) {
        for (const auto& a : profile.common_args) c.argv.push_back(a);
      }
      width_ = std::max(width_, c.spec->name.size());
      children_.push_back(std::move(c));
    }
  }

  int run(double grace_s) {
    for (auto& c : children_) {
      if (shutdown_requested() || stop_) break;
      start(c);
      const auto until = after_seconds(c.spec->start_delay_s);
      while (Clock::now() < until && !shutdown_requested() && !stop_) step(50);
    }
    while (!stop_ && !shutdown_requested() && anything_alive()) step(100);
    if (shutdown_requested()) say("launch", "stopping (signal received)");
    stop_all(grace_s);
    return failed_required_ ? 1 : 0;
  }

 private:
  void say(const std::string& who, const std::string& line) {
    std::printf("[%-*s] %s\n", static_cast<int>(width_), who.c_str(), line.c_str());
    std::fflush(stdout);
  }

  void start(Child& c) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe() failed");
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork() failed");
    if (pid == 0) {
      ::setpgid(0, 0);  // Ctrl-C on the terminal reaches the launcher only; it stops children in order
      ::dup2(fds[1], STDOUT_FILENO);
      ::dup2(fds[1], STDERR_FILENO);
      ::close(fds[0]);
      ::close(fds[1]);
      for (const auto& [k, v] : c.spec->env) ::setenv(k.c_str(), v.c_str(), 1);
      std::vector<char*> args;
      for (auto& a : c.argv) args.push_back(const_cast<char*>(a.c_str()));
      if (c.respawns > 0) {
        for (auto& a : c.spec->respawn_args) args.push_back(const_cast<char*>(a.c_str()));
      }
      args.push_back(nullptr);
      ::execv(c.program.c_str(), args.data());
      std::fprintf(stderr, "cannot run %s: %s\n", c.program.c_str(), std::strerror(errno));
      ::_exit(127);
    }
    ::close(fds[1]);
    ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
    c.pid = pid;
    c.out_fd = fds[0];
    c.respawn_at.reset();
    c.started_at = Clock::now();
    c.hung = false;
    std::string cmd;
    for (size_t i = 1; i < c.argv.size(); ++i) cmd += " " + c.argv[i];
    if (c.respawns > 0) {
      for (const auto& a : c.spec->respawn_args) cmd += " " + a;
    }
    say("launch", "started " + c.spec->name + " (pid " + std::to_string(pid) + "): " +
                      std::filesystem::path(c.program).filename().string() + cmd);
  }

  bool anything_alive() const {
    for (const auto& c : children_) {
      if (c.pid > 0 || c.respawn_at) return true;
    }
    return false;
  }

  // Forwards output, reaps exits, starts due respawns.
  void step(int timeout_ms) {
    std::vector<pollfd> fds;
    for (auto& c : children_) {
      if (c.out_fd >= 0) fds.push_back({c.out_fd, POLLIN, 0});
    }
    if (!fds.empty()) ::poll(fds.data(), fds.size(), timeout_ms);
    else std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    for (auto& c : children_) read_output(c, false);
    watch_health();
    for (auto& c : children_) reap(c);
    for (auto& c : children_) {
      if (c.respawn_at && Clock::now() >= *c.respawn_at && !stop_ && !shutdown_requested()) start(c);
    }
  }

  // A process that reported on uavmot/health and then fell silent for its hang_timeout while still
  // alive hangs (its own writers' waits keep the reports going, so backpressure is not silence).
  // So does one that has not reported within hang_timeout of its start (every watched component
  // reports once its participant is up, well under a second here): stuck before its first report,
  // it would otherwise hold its upstream waiting for a reader until that gives up and fails the launch.
  // SIGKILL works on a stopped process too; reap() then respawns it like any crash.
  void watch_health() {
    if (!health_ || stop_ || shutdown_requested()) return;
    health_->poll();
    for (auto& c : children_) {
      if (c.pid <= 0 || c.hung || c.spec->hang_timeout_s <= 0.0) continue;
      char line[200];
      if (const auto silent = health_->silent_s(c.pid, c.spec->command)) {
        if (*silent < c.spec->hang_timeout_s) continue;
        std::snprintf(line, sizeof(line), "%s (pid %d) hangs: no health report for %.1f s (hang_timeout %.1f s); killing it",
                      c.spec->name.c_str(), static_cast<int>(c.pid), *silent, c.spec->hang_timeout_s);
      } else {
        const double since_start = std::chrono::duration<double>(Clock::now() - c.started_at).count();
        if (health_->reported(c.pid, c.spec->command) || since_start < c.spec->hang_timeout_s) continue;
        std::snprintf(line, sizeof(line),
                      "%s (pid %d) hangs: no health report in the %.1f s since its start (hang_timeout %.1f s); killing it",
                      c.spec->name.c_str(), static_cast<int>(c.pid), since_start, c.spec->hang_timeout_s);
      }
      say("launch", line);
      c.hung = true;
      ::kill(c.pid, SIGKILL);
    }
  }

  void read_output(Child& c, bool to_eof) {
    if (c.out_fd < 0) return;
    char buffer[4096];
    while (true) {
      const ssize_t n = ::read(c.out_fd, buffer, sizeof(buffer));
      if (n > 0) {
        c.partial_line.append(buffer, static_cast<size_t>(n));
        size_t eol;
        while ((eol = c.partial_line.find('\n')) != std::string::npos) {
          say(c.spec->name, c.partial_line.substr(0, eol));
          c.partial_line.erase(0, eol + 1);
        }
        continue;
      }
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
        if (!c.partial_line.empty()) say(c.spec->name, c.partial_line);
        c.partial_line.clear();
        ::close(c.out_fd);
        c.out_fd = -1;
        return;
      }
      if (!to_eof) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  void reap(Child& c) {
    if (c.pid <= 0) return;
    int status = 0;
    if (::waitpid(c.pid, &status, WNOHANG) != c.pid) return;
    c.pid = -1;
    read_output(c, true);
    const bool failed = !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    const std::string what = c.spec->name + " " + (c.hung ? "hung, " : "") + describe_status(status);
    if (failed && c.spec->respawn && c.respawns < c.spec->max_respawns && !stop_ && !shutdown_requested()) {
      ++c.respawns;
      c.respawn_at = after_seconds(c.spec->respawn_delay_s);
      char delay[32];
      std::snprintf(delay, sizeof(delay), "%.1f", c.spec->respawn_delay_s);
      say("launch", what + "; respawning in " + delay + " s (" + std::to_string(c.respawns) + "/" +
                        std::to_string(c.spec->max_respawns) + ")");
      return;
    }
    c.finished = true;
    if (failed && c.spec->respawn) say("launch", what + "; no respawns left");
    else say("launch", what);
    if (failed && c.spec->stop_on_failure && !c.spec->required) {
      failed_required_ = true;
      say("launch", c.spec->name + " failed: stopping the launch");
      stop_ = true;
    }
    if (c.spec->required) {
      if (failed) {
        failed_required_ = true;
        say("launch", "required process " + c.spec->name + " failed: stopping the launch");
      } else {
        say("launch", "required process " + c.spec->name + " finished: stopping the launch");
      }
      stop_ = true;
    }
  }

  // Reverse start order: the source stops first, the sink, which writes the results, last.
  void stop_all(double grace_s) {
    for (auto& c : children_) c.respawn_at.reset();
    for (auto it = children_.rbegin(); it != children_.rend(); ++it) {
      Child& c = *it;
      if (c.pid <= 0) continue;
      say("launch", "stopping " + c.spec->name);
      ::kill(c.pid, SIGINT);
      const auto deadline = after_seconds(grace_s);
      while (c.pid > 0 && Clock::now() < deadline) {
        step(50);
      }
      if (c.pid > 0) {
        say("launch", c.spec->name + " did not stop within the grace period: SIGKILL");
        ::kill(c.pid, SIGKILL);
        while (c.pid > 0) step(50);
      }
    }
    for (auto& c : children_) read_output(c, true);
  }

  std::vector<Child> children_;
  HealthMonitor* health_ = nullptr;
  size_t width_ = 6;
  bool stop_ = false;
  bool failed_required_ = false;
};

}  // namespace

Supervisor::Supervisor(Profile resolved, SupervisorOptions options) : profile_(std::move(resolved)), options_(std::move(options)) {
  namespace fs = std::filesystem;
  for (const auto& p : profile_.processes) {
    const fs::path program = p.command.find('/') != std::string::npos ? fs::path(p.command)
                                                                      : fs::path(options_.bin_dir) / ("uavmot-" + p.command);
    if (::access(program.c_str(), X_OK) != 0) {
      throw InputError(profile_.file + ": process '" + p.name + "': command '" + p.command + "' (" + program.string() +
                       ") is not an executable uavmot program");
    }
    programs_.push_back(program.string());
  }
}

int Supervisor::run() {
  ::signal(SIGPIPE, SIG_IGN);
  Runner runner(profile_, programs_, options_.health);
  return runner.run(options_.shutdown_grace_s);
}

}  // namespace uavmot::launch
