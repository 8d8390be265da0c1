#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot::build_paths {

std::string source_dir() { return UAVMOT_BUILD_SOURCE_DIR; }
std::string binary_dir() { return UAVMOT_BUILD_BINARY_DIR; }
std::string data_dir() { return UAVMOT_BUILD_DATA_DIR; }

}  // namespace uavmot::build_paths
