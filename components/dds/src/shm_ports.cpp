#include "shm_ports.hpp"

#include <filesystem>

namespace uavmot::dds {

std::pair<uint32_t, uint32_t> unicast_ports(int domain, int participant_id) {
  const uint32_t metatraffic = 7400 + 250 * static_cast<uint32_t>(domain) + 10 + 2 * static_cast<uint32_t>(participant_id);
  return {metatraffic, metatraffic + 1};
}

int fresh_participant_id(int domain, const std::string& shm_dir, int limit) {
  namespace fs = std::filesystem;
  auto used = [&](uint32_t port) {
    // The port's segment, or the lock file that outlives it.
    const std::string name = shm_dir + "/fastrtps_port" + std::to_string(port);
    std::error_code ec;
    return fs::exists(name, ec) || fs::exists(name + "_el", ec);
  };
  for (int id = 0; id < limit; ++id) {
    const auto [metatraffic, user] = unicast_ports(domain, id);
    if (!used(metatraffic) && !used(user)) return id;
  }
  return -1;
}

}  // namespace uavmot::dds
