#include "motion_state_file.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "uavmot/core/error.hpp"

namespace uavmot::motion {

std::optional<std::vector<uint8_t>> load_state_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("motion state file '" + path + "' cannot be opened");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("motion state file '" + path + "' cannot be read");
  return bytes;
}

}  // namespace uavmot::motion
