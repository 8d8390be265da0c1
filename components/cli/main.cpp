// uavmot: the umbrella command. `uavmot SUB ARGS...` runs the executable `uavmot-SUB` found beside
// this one (or on PATH), git-style, so every component also runs on its own.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr const char* kPrefix = "uavmot-";

fs::path own_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::current_path() : exe.parent_path();
}

// Subcommands: every executable uavmot-* beside us.
std::map<std::string, fs::path> find_subcommands() {
  std::map<std::string, fs::path> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(own_dir(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kPrefix, 0) == 0 && ::access(entry.path().c_str(), X_OK) == 0) {
      found.emplace(name.substr(std::strlen(kPrefix)), entry.path());
    }
  }
  return found;
}

std::string describe(const fs::path& exe) {
  const std::string cmd = "'" + exe.string() + "' --describe 2>/dev/null";
  std::string out;
  if (FILE* pipe = ::popen(cmd.c_str(), "r")) {
    std::array<char, 256> buffer{};
    if (std::fgets(buffer.data(), buffer.size(), pipe)) out = buffer.data();
    ::pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

void print_help(const std::map<std::string, fs::path>& subcommands) {
  std::cout << "uavmot: detection, segmentation and tracking of moving objects in UAV video\n\n"
               "usage: uavmot SUBCOMMAND [ARGS...]\n"
               "       uavmot SUBCOMMAND --help\n\n"
               "subcommands:\n";
  size_t width = 0;
  for (const auto& [name, path] : subcommands) width = std::max(width, name.size());
  for (const auto& [name, path] : subcommands) {
    std::cout << "  " << name << std::string(width - name.size() + 2, ' ') << describe(path) << "\n";
  }
  std::cout << "\nEach subcommand is also the program uavmot-SUBCOMMAND.\n";
}

}  // namespace

int main(int argc, char** argv) {
  const auto subcommands = find_subcommands();
  // `uavmot help SUB` is `uavmot SUB --help`; the rewritten arguments live as long as main().
  std::vector<char*> help_args;
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    if (argc >= 3 && !std::strcmp(argv[1], "help")) {
      help_args = {argv[0], argv[2], const_cast<char*>("--help")};
      argv = help_args.data();
      argc = 3;
    } else {
      print_help(subcommands);
      return argc < 2 ? 2 : 0;
    }
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::cout << "uavmot 0.1.0\n";
    return 0;
  }
  const std::string sub = argv[1];
  const auto it = subcommands.find(sub);
  if (it == subcommands.end()) {
    std::cerr << "uavmot: '" << sub << "' is not a uavmot subcommand. See 'uavmot --help'.\n";
    return 2;
  }
  std::vector<char*> args;
  std::string program = it->second.string();
  args.push_back(program.data());
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  ::execv(program.c_str(), args.data());
  std::cerr << "uavmot: cannot run '" << program << "': " << std::strerror(errno) << "\n";
  return 1;
}
