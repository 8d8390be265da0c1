#include "../src/shm_ports.hpp"

#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "uavmot/dds/participant.hpp"

namespace uavmot::dds {
namespace {
namespace fs = std::filesystem;

void touch(const fs::path& file) { std::ofstream(file).put('\n'); }

TEST(ShmPorts, FollowFastDdsDefaultPortMapping) {
  EXPECT_EQ(unicast_ports(0, 0), std::make_pair(7410u, 7411u));
  EXPECT_EQ(unicast_ports(36, 1), std::make_pair(16412u, 16413u));
}

TEST(ShmPorts, TheFirstIdWithoutAnySegmentOrLockFileIsChosen) {
  const fs::path dir = fs::temp_directory_path() / ("uavmot_shm_ports_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_EQ(fresh_participant_id(36, dir.string()), 0);
  touch(dir / "fastrtps_port16410");  // id 0's metatraffic segment (a live or crashed process)
  EXPECT_EQ(fresh_participant_id(36, dir.string()), 1);
  touch(dir / "fastrtps_port16413_el");  // only the lock file of id 1's user port is left
  EXPECT_EQ(fresh_participant_id(36, dir.string()), 2);
  touch(dir / "fastrtps_port16662");  // another domain's ports do not matter
  EXPECT_EQ(fresh_participant_id(36, dir.string()), 2);
  EXPECT_EQ(fresh_participant_id(36, dir.string(), 2), -1);
  fs::remove_all(dir);
}

// The ports whose lock files this process holds open.
std::set<std::string> held_ports() {
  std::set<std::string> held;
  for (const auto& fd : fs::directory_iterator("/proc/self/fd")) {
    std::error_code ec;
    const std::string target = fs::read_symlink(fd.path(), ec).filename().string();
    if (!ec && target.rfind("fastrtps_port", 0) == 0) held.insert(target);
  }
  return held;
}

TEST(ShmPorts, AParticipantDoesNotTakeOverTheSegmentsACrashedProcessLeft) {
  constexpr int kDomain = 93;
  const auto [meta0, user0] = unicast_ports(kDomain, 0);
  const auto [meta1, user1] = unicast_ports(kDomain, 1);
  // What a SIGKILLed participant with id 0 leaves behind.
  const fs::path zombie = "/dev/shm/fastrtps_port" + std::to_string(meta0);
  touch(zombie);
  {
    DdsOptions options;
    options.domain_id = kDomain;
    Participant participant(options);
    const auto held = held_ports();
    EXPECT_FALSE(held.count("fastrtps_port" + std::to_string(meta0) + "_el"));
    EXPECT_FALSE(held.count("fastrtps_port" + std::to_string(user0) + "_el"));
    EXPECT_TRUE(held.count("fastrtps_port" + std::to_string(meta1) + "_el") ||
                held.count("fastrtps_port" + std::to_string(user1) + "_el"))
        << "expected the ports of participant id 1";
  }
  fs::remove(zombie);
}

}  // namespace
}  // namespace uavmot::dds
