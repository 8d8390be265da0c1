#pragma once
// Choosing a participant id whose shared-memory ports no earlier process used.
//
// Fast DDS 2.9 names a participant's shared-memory ports after its unicast ports. A process that
// is SIGKILLed leaves its ports behind as "zombies"; a respawned process is given the same ports,
// finds them zombie, deletes and recreates the segments, while the writers of the processes that
// stayed up keep pushing into the deleted ones: the respawned reader never receives a sample and
// the lossless chain stalls (eProsima/Fast-DDS#4728, fixed only after 2.9). Starting every
// participant on ports that have no segment at all avoids the reuse.
//
// Every crash leaves two more port segments, and a domain has only 120 participant ids. Once every
// id has left something behind (a long-lived host, a CI machine), the ports that no live process
// holds (open or mapped) are deleted and their ids used again: no writer can still push into them.

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>

namespace uavmot::dds {

// The (metatraffic, user) unicast ports of `participant_id` on `domain`: Fast DDS's default port
// mapping, 7400 + 250 * domain + 10 (+ 1) + 2 * participant_id.
std::pair<uint32_t, uint32_t> unicast_ports(int domain, int participant_id);

// The lowest participant id below `limit`, not in `skip`, whose two unicast ports have no
// shared-memory segment in `shm_dir`; -1 if every one has.
int fresh_participant_id(int domain, const std::string& shm_dir = "/dev/shm", int limit = 120, const std::set<int>& skip = {});

// The shared-memory ports that a live process holds open (a listener's lock file) or mapped (a
// listener's segment or mutex, or one a writer pushes into), from /proc/<pid>/fd and /maps;
// nullopt when `proc_dir` does not list this process (no /proc, or another pid namespace's),
// since then nothing can be known to be free.
std::optional<std::set<uint32_t>> ports_in_use(const std::string& proc_dir = "/proc");

// Deletes the segment, lock file and mutex of every port of `domain` (ids below `limit`) whose
// participant id has left files in `shm_dir` while neither of its ports is in `in_use`. Returns the
// number of ids freed.
int reclaim_abandoned_ports(int domain, const std::set<uint32_t>& in_use, const std::string& shm_dir = "/dev/shm",
                            int limit = 120);

// Held from choosing an id until the participant has created its ports: processes starting
// together on one domain neither pick the same fresh id nor delete each other's new ports as
// abandoned. An exclusive flock on a file in `shm_dir`; without one (no such directory) it holds nothing.
class ParticipantIdLock {
 public:
  explicit ParticipantIdLock(int domain, const std::string& shm_dir = "/dev/shm");
  ~ParticipantIdLock();
  ParticipantIdLock(const ParticipantIdLock&) = delete;
  ParticipantIdLock& operator=(const ParticipantIdLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace uavmot::dds
