// libFuzzer entry point; the CMake target defines UAVMOT_FUZZ_ENTRY as one of fuzz_targets.hpp.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return UAVMOT_FUZZ_ENTRY(data, size); }
