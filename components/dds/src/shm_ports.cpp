#include "shm_ports.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <vector>

namespace uavmot::dds {
namespace fs = std::filesystem;
namespace {

const std::string kPortPrefix = "fastrtps_port";

// The port number in a /dev/shm name such as ".../fastrtps_port16410_el" or "sem.fastrtps_port16410_mutex".
bool port_in_name(const std::string& name, uint32_t& port) {
  const auto at = name.find(kPortPrefix);
  if (at == std::string::npos) return false;
  size_t i = at + kPortPrefix.size();
  uint64_t value = 0;
  const size_t first = i;
  while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i])) && i - first < 9) {
    value = value * 10 + static_cast<uint64_t>(name[i] - '0');
    ++i;
  }
  if (i == first) return false;
  port = static_cast<uint32_t>(value);
  return true;
}

// The port's segment, its lock file and its mutex, as Fast DDS names them.
std::vector<fs::path> files_of_port(const std::string& shm_dir, uint32_t port) {
  const std::string name = kPortPrefix + std::to_string(port);
  return {fs::path(shm_dir) / name, fs::path(shm_dir) / (name + "_el"), fs::path(shm_dir) / ("sem." + name + "_mutex")};
}

bool port_left_files(const std::string& shm_dir, uint32_t port) {
  std::error_code ec;
  for (const auto& file : files_of_port(shm_dir, port)) {
    if (fs::exists(file, ec)) return true;
  }
  return false;
}

}  // namespace

std::pair<uint32_t, uint32_t> unicast_ports(int domain, int participant_id) {
  const uint32_t metatraffic = 7400 + 250 * static_cast<uint32_t>(domain) + 10 + 2 * static_cast<uint32_t>(participant_id);
  return {metatraffic, metatraffic + 1};
}

int fresh_participant_id(int domain, const std::string& shm_dir, int limit, const std::set<int>& skip) {
  auto used = [&](uint32_t port) {
    // The port's segment, or the lock file that outlives it.
    const std::string name = shm_dir + "/" + kPortPrefix + std::to_string(port);
    std::error_code ec;
    return fs::exists(name, ec) || fs::exists(name + "_el", ec);
  };
  for (int id = 0; id < limit; ++id) {
    if (skip.count(id)) continue;
    const auto [metatraffic, user] = unicast_ports(domain, id);
    if (!used(metatraffic) && !used(user)) return id;
  }
  return -1;
}

std::optional<std::set<uint32_t>> ports_in_use(const std::string& proc_dir) {
  std::set<uint32_t> in_use;
  const std::string self = std::to_string(::getpid());
  bool saw_self = false;
  std::error_code ec;
  for (const auto& process : fs::directory_iterator(proc_dir, ec)) {
    const std::string pid = process.path().filename().string();
    if (pid.empty() || !std::isdigit(static_cast<unsigned char>(pid[0]))) continue;
    saw_self = saw_self || pid == self;
    uint32_t port = 0;
    std::error_code fd_ec;
    for (const auto& fd : fs::directory_iterator(process.path() / "fd", fd_ec)) {
      std::error_code link_ec;
      const std::string target = fs::read_symlink(fd.path(), link_ec).string();
      if (!link_ec && port_in_name(target, port)) in_use.insert(port);
    }
    std::ifstream maps(process.path() / "maps");
    for (std::string line; std::getline(maps, line);) {
      if (port_in_name(line, port)) in_use.insert(port);
    }
  }
  if (ec || !saw_self) return std::nullopt;
  return in_use;
}

int reclaim_abandoned_ports(int domain, const std::set<uint32_t>& in_use, const std::string& shm_dir, int limit) {
  int freed = 0;
  for (int id = 0; id < limit; ++id) {
    const auto [metatraffic, user] = unicast_ports(domain, id);
    if (in_use.count(metatraffic) || in_use.count(user)) continue;
    if (!port_left_files(shm_dir, metatraffic) && !port_left_files(shm_dir, user)) continue;
    std::error_code ec;
    for (const uint32_t port : {metatraffic, user}) {
      for (const auto& file : files_of_port(shm_dir, port)) fs::remove(file, ec);
    }
    ++freed;
  }
  return freed;
}

ParticipantIdLock::ParticipantIdLock(int domain, const std::string& shm_dir) {
  const std::string file = shm_dir + "/uavmot_participant_ids_" + std::to_string(domain) + ".lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

ParticipantIdLock::~ParticipantIdLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

}  // namespace uavmot::dds
