#pragma once
// What the DDS tests share: a participant's options on the test's own domain (test binaries run in
// parallel must not see each other), and waiting until a writer's readers are gone.

#include <chrono>
#include <string>
#include <thread>

#include "uavmot/dds/participant.hpp"

namespace uavmot::dds::test_support {

inline DdsOptions options_on(int domain, const std::string& name, const std::string& profiles_file = "",
                             const std::string& profile = "local") {
  DdsOptions o;
  o.domain_id = domain;
  o.participant_name = name;
  o.profiles_file = profiles_file;
  o.participant_profile = profile;
  return o;
}

// Waits until no reader is matched to `writer` any more (a deleted reader participant says so at
// once; a vanished one is dropped after the profiles' 5 s lease); true if none is left in time.
template <class Writer>
bool wait_until_unmatched(const Writer& writer, std::chrono::seconds timeout = std::chrono::seconds(15)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (writer.matched() > 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return writer.matched() == 0;
}

}  // namespace uavmot::dds::test_support
