#pragma once
// The absolute folders of this build, as CMake configured it. They are compiled into one object
// (src/build_paths.cpp) instead of every object that uses them, so that the others hit ccache in
// another clone of the repository (components/build_paths/CMakeLists.txt).

#include <string>

namespace uavmot::build_paths {

std::string source_dir();  // the repository (CMAKE_SOURCE_DIR)
std::string binary_dir();  // the build folder (CMAKE_BINARY_DIR)
std::string data_dir();    // the real imagery (CMake cache variable UAVMOT_DATA_DIR, default <source>/data)

}  // namespace uavmot::build_paths
