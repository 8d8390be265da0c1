// uavmot-test-abandon-ports DOMAIN [COUNT]: creates COUNT (default 120, every id) shared-memory
// participants on DOMAIN and SIGKILLs itself, leaving real zombie port segments on every id, as a
// host that has seen many crashes has them. For tests of participant id choice after crashes.

#include <signal.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "uavmot/dds/participant.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DOMAIN [COUNT]\n", argv[0]);
    return 2;
  }
  uavmot::dds::DdsOptions options;
  options.domain_id = std::atoi(argv[1]);
  options.participant_name = "abandoned";
  const int count = argc > 2 ? std::atoi(argv[2]) : 120;
  std::vector<std::unique_ptr<uavmot::dds::Participant>> participants;
  for (int i = 0; i < count; ++i) participants.push_back(std::make_unique<uavmot::dds::Participant>(options));
  std::printf("%d participants on domain %d; killing myself\n", count, options.domain_id);
  std::fflush(stdout);
  ::raise(SIGKILL);
  return 1;
}
