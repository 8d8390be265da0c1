// uavmot-test-abandon-ports DOMAIN [COUNT]: creates COUNT (default 120, every id) shared-memory
// participants on DOMAIN and SIGKILLs itself, leaving real zombie port segments on every id, as a
// host that has seen many crashes has them. For tests of participant id choice after crashes.

#include <signal.h>

#include <charconv>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "uavmot/dds/participant.hpp"

namespace {

// `text` as a whole number in [low, high], or false.
bool parse_int(const std::string& text, int low, int high, int& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && value >= low && value <= high;
}

}  // namespace

int main(int argc, char** argv) {
  int domain = 0;
  int count = 120;
  if (argc < 2 || argc > 3 || !parse_int(argv[1], 0, 232, domain) || (argc == 3 && !parse_int(argv[2], 1, 120, count))) {
    std::fprintf(stderr, "usage: %s DOMAIN [COUNT]   (DOMAIN 0-232, COUNT 1-120, default 120)\n", argv[0]);
    return 2;
  }
  uavmot::dds::DdsOptions options;
  options.domain_id = domain;
  options.participant_name = "abandoned";
  std::vector<std::unique_ptr<uavmot::dds::Participant>> participants;
  try {
    for (int i = 0; i < count; ++i) participants.push_back(std::make_unique<uavmot::dds::Participant>(options));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
  std::printf("%d participants on domain %d; killing myself\n", count, domain);
  std::fflush(stdout);
  ::raise(SIGKILL);
  return 1;
}
