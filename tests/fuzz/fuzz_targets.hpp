#pragma once
// The fuzz targets as plain functions: libfuzzer_main.cpp makes each a libFuzzer binary
// (tools/fuzz.sh), and fuzz_replay_test runs the committed seeds and every input that once
// crashed (tests/fuzz/regressions/<target>/) through the same function in the normal build.
// Each returns 0; anything else that escapes (a crash, a foreign exception) is a finding.

#include <cstddef>
#include <cstdint>

namespace uavmot::fuzz {

int mcap_reader(const uint8_t* data, size_t size);        // MCAP bytes -> Reader
int sample_validators(const uint8_t* data, size_t size);  // CDR bytes -> chain/downlink/state samples -> validation
int config(const uint8_t* data, size_t size);             // YAML text -> ConfigNode, scene, launch profile
int eval_files(const uint8_t* data, size_t size);         // first byte picks the file kind, rest is its text
int recording(const uint8_t* data, size_t size);          // MCAP bytes -> eval --recording, recover, again
int motion_state(const uint8_t* data, size_t size);       // bytes -> MotionEstimator::restore_state, two frames
int segmentation_state(const uint8_t* data, size_t size); // bytes -> Segmenter::restore_state, two frames

}  // namespace uavmot::fuzz
