#pragma once
// Choosing a participant id whose shared-memory ports no earlier process used.
//
// Fast DDS 2.9 names a participant's shared-memory ports after its unicast ports. A process that
// is SIGKILLed leaves its ports behind as "zombies"; a respawned process is given the same ports,
// finds them zombie, deletes and recreates the segments, while the writers of the processes that
// stayed up keep pushing into the deleted ones: the respawned reader never receives a sample and
// the lossless chain stalls (eProsima/Fast-DDS#4728, fixed only after 2.9). Starting every
// participant on ports that have no segment at all avoids the reuse.

#include <cstdint>
#include <string>
#include <utility>

namespace uavmot::dds {

// The (metatraffic, user) unicast ports of `participant_id` on `domain`: Fast DDS's default port
// mapping, 7400 + 250 * domain + 10 (+ 1) + 2 * participant_id.
std::pair<uint32_t, uint32_t> unicast_ports(int domain, int participant_id);

// The lowest participant id below `limit` whose two unicast ports have no shared-memory segment in
// `shm_dir`; -1 if every one has (the caller then leaves the choice to Fast DDS).
int fresh_participant_id(int domain, const std::string& shm_dir = "/dev/shm", int limit = 120);

}  // namespace uavmot::dds
