#include "../src/shm_ports.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <unistd.h>

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

// An id another participant of this process has (on another domain) is skipped although its ports
// on this domain are fresh.
TEST(ShmPorts, IdsTakenInThisProcessAreSkipped) {
  const fs::path dir = fs::temp_directory_path() / ("uavmot_shm_ports_skip_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_EQ(fresh_participant_id(36, dir.string(), 120, {0}), 1);
  EXPECT_EQ(fresh_participant_id(36, dir.string(), 120, {0, 1, 3}), 2);
  EXPECT_EQ(fresh_participant_id(36, dir.string(), 2, {0, 1}), -1);
  fs::remove_all(dir);
}

// Two participants in one process, one on a UDP-only domain (Fast DDS picks its id) and one with
// shared memory on another domain (uavmot picks a fresh id): both are made, as the launcher's
// watchdog needs when it watches the air chain and the downlink.
TEST(ShmPorts, ParticipantsOnTwoDomainsInOneProcess) {
  DdsOptions udp;
  udp.domain_id = 37;
  udp.participant_profile = "udp";
  udp.participant_name = "udp_side";
  DdsOptions local;
  local.domain_id = 38;
  local.participant_profile = "local";
  local.participant_name = "shm_side";
  Participant first(udp);
  EXPECT_NO_THROW(Participant second(local));
}

// All three files Fast DDS keeps for a port.
void leave_port_files(const fs::path& dir, uint32_t port) {
  const std::string name = "fastrtps_port" + std::to_string(port);
  touch(dir / name);
  touch(dir / (name + "_el"));
  touch(dir / ("sem." + name + "_mutex"));
}

TEST(ShmPorts, OnlyPortsNoLiveProcessHoldsAreReclaimed) {
  const fs::path dir = fs::temp_directory_path() / ("uavmot_shm_reclaim_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (int id = 0; id < 4; ++id) {
    leave_port_files(dir, unicast_ports(36, id).first);
    leave_port_files(dir, unicast_ports(36, id).second);
  }
  ASSERT_EQ(fresh_participant_id(36, dir.string(), 4), -1);
  // Id 1's user port is still held by a live process (a listener, or a writer pushing into it).
  const std::set<uint32_t> in_use = {unicast_ports(36, 1).second};
  EXPECT_EQ(reclaim_abandoned_ports(36, in_use, dir.string(), 4), 3);
  EXPECT_TRUE(fs::exists(dir / "fastrtps_port16412"));  // id 1's other port stays with it
  EXPECT_TRUE(fs::exists(dir / "sem.fastrtps_port16413_mutex"));
  EXPECT_FALSE(fs::exists(dir / "fastrtps_port16410"));
  EXPECT_FALSE(fs::exists(dir / "fastrtps_port16411_el"));
  EXPECT_FALSE(fs::exists(dir / "sem.fastrtps_port16417_mutex"));
  EXPECT_EQ(fresh_participant_id(36, dir.string(), 4), 0);
  EXPECT_EQ(reclaim_abandoned_ports(36, in_use, dir.string(), 4), 0);  // nothing more to free
  fs::remove_all(dir);
}

TEST(ShmPorts, PortsInUseAreTheOnesAProcessHoldsOpenOrMapped) {
  const fs::path dir = fs::temp_directory_path() / ("uavmot_shm_in_use_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  touch(dir / "fastrtps_port64001_el");
  touch(dir / "fastrtps_port64002");
  touch(dir / "fastrtps_port64003");
  ASSERT_TRUE(ports_in_use().has_value());
  EXPECT_FALSE(ports_in_use()->count(64001));
  // A directory that does not list this process cannot say which ports are free.
  EXPECT_FALSE(ports_in_use(dir.string()).has_value());
  std::ifstream lock_file(dir / "fastrtps_port64001_el");  // held open, as a listener holds its lock
  const int fd = ::open((dir / "fastrtps_port64002").c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  void* mapped = ::mmap(nullptr, 1, PROT_READ, MAP_SHARED, fd, 0);  // mapped, as a writer maps a port
  ASSERT_NE(mapped, MAP_FAILED);
  ::close(fd);
  const std::set<uint32_t> in_use = ports_in_use().value();
  EXPECT_TRUE(in_use.count(64001));
  EXPECT_TRUE(in_use.count(64002));
  EXPECT_FALSE(in_use.count(64003));
  ::munmap(mapped, 1);
  fs::remove_all(dir);
}

// Whether someone else could take the id lock of `domain` in `dir` right now: flock() treats every
// open() of a file as its own lock holder, in this process as in another.
bool someone_else_can_lock(const fs::path& dir, int domain) {
  const std::string file = (dir / ("uavmot_participant_ids_" + std::to_string(domain) + ".lock")).string();
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT, 0644);
  const bool locked = fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  if (fd >= 0) ::close(fd);
  return locked;
}

TEST(ShmPorts, ChoosingAnIdIsOneProcessAtATimePerDomain) {
  const fs::path dir = fs::temp_directory_path() / ("uavmot_shm_lock_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    ParticipantIdLock held(36, dir.string());
    EXPECT_FALSE(someone_else_can_lock(dir, 36));
    EXPECT_TRUE(someone_else_can_lock(dir, 37));  // another domain is not held up
  }
  EXPECT_TRUE(someone_else_can_lock(dir, 36));
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

TEST(ShmPorts, AParticipantFindsAnIdWhenEveryIdHasLeftPortsBehind) {
  // A host where crashed participants have left ports on every id of the domain: without reclaiming,
  // Fast DDS would put the new participant on a zombie's ports (eProsima/Fast-DDS#4728).
  constexpr int kDomain = 92;
  for (int id = 0; id < 120; ++id) {
    leave_port_files("/dev/shm", unicast_ports(kDomain, id).first);
    leave_port_files("/dev/shm", unicast_ports(kDomain, id).second);
  }
  {
    DdsOptions options;
    options.domain_id = kDomain;
    Participant participant(options);
    const auto held = held_ports();
    const auto [meta0, user0] = unicast_ports(kDomain, 0);
    EXPECT_TRUE(held.count("fastrtps_port" + std::to_string(meta0) + "_el") ||
                held.count("fastrtps_port" + std::to_string(user0) + "_el"))
        << "expected the reclaimed ports of participant id 0";
    EXPECT_FALSE(fs::exists("/dev/shm/fastrtps_port" + std::to_string(unicast_ports(kDomain, 119).first)));
  }
  reclaim_abandoned_ports(kDomain, {});  // the participant is gone: nothing of this domain is held
}

}  // namespace
}  // namespace uavmot::dds
