#pragma once
// Shared inputs of the geo tests: the repo's aphill clip and small byte helpers.

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot::geo::test {

inline std::string aphill_ts_path() { return build_paths::data_dir() + "/aphill/aphill_short.ts"; }

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) bytes.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return bytes;
}

// The ST 0601 example packet of MISB ST 0601 (as printed in the misb.js README, vidterra/misb.js).
inline const char* kMisbExample0601Hex =
    "060E2B34020B01010E0103010100000081D2020800046050584E0180030A4D697373696F6E20"
    "3132050271C20602FD3D070208B80A085072656461746F720B07454F204E6F73650C0E47656F"
    "64657469632057475338340D045595B66D0E045B5360C40F02C2211002CD9C1102D917120472"
    "4A0A20130487F84B86140400000000150403830926160212811704F101A229180414BC082B19"
    "0234F3301C01010102010703052F2F5553410C01070D060055005300411602000A4101065E22"
    "0170F592F02373364AF8AA9162C00F2EB2DA16B74341000841A0BE365B5AB96A36450102AA43";

// A hand-made ST 0601 packet with every tag the decoder reads (misb0601_test.cpp decodes it by
// hand, field by field): raw integers chosen by hand, checksum computed with the standard's sum.
inline const char* kHandMade0601Hex =
    "060E2B34020B01010E0103010100000081B502080004573E5AEE5400410111050240000602FC18070280000D04366B46400E04C8FC2340"
    "0F0227101002012C110200C81204400000001304EE1E5D0014040000000015040016E3601602001417043666B2601804C8FA9CA019021388"
    "1A0200641B02FF381C02FF6A1D02FF881E02FFA61F0200D22002008C210200A052043675F4A05304C8DC18205404364FCF005504C8E84D20"
    "56043658F6C05704C91AA7C05804367C0F205904C91306A0810201070102144A";

}  // namespace uavmot::geo::test
