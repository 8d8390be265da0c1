#pragma once
// The segmentation methods. They are listed once, in the enum SegmentationMethod of
// idl/segmentation.idl (the wire contract); the build writes that list as the X-macro
// UAVMOT_SEGMENTATION_METHODS(X) into uavmot/core/segmentation_methods.inc
// (cmake/segmentation_methods_from_idl.cmake), so core reads the IDL's text and never Fast DDS.
// X(enumerator, name): IDL KORN -> X(Korn, "korn"); SOME_METHOD -> X(SomeMethod, "some_method").
// A method's name is how configs, command lines and the tracker's region_method spell it; its
// position in the list is its number on the wire. Append only: recordings keep the numbers.
// Adding a method: docs/developing.md, "Worked example: add a segmentation method".

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "uavmot/core/segmentation_methods.inc"

namespace uavmot {

enum class SegmentationMethod : uint8_t {
#define UAVMOT_METHOD_ENUMERATOR(enumerator, name) enumerator,
  UAVMOT_SEGMENTATION_METHODS(UAVMOT_METHOD_ENUMERATOR)
#undef UAVMOT_METHOD_ENUMERATOR
};

// Every method, in list order.
inline constexpr std::array kSegmentationMethods = {
#define UAVMOT_METHOD_VALUE(enumerator, name) SegmentationMethod::enumerator,
    UAVMOT_SEGMENTATION_METHODS(UAVMOT_METHOD_VALUE)
#undef UAVMOT_METHOD_VALUE
};

const char* to_string(SegmentationMethod method);
// Throws uavmot::InvalidArgument naming the accepted values.
SegmentationMethod parse_segmentation_method(const std::string& name);
// The names in list order, for command-line and YAML choices.
std::vector<std::string> segmentation_method_names();
// "clustering, korn, morphological, lbp or fusion", for help texts and messages.
std::string segmentation_method_choices();
// Whether a number from the wire names a method.
bool is_segmentation_method(uint64_t value);

}  // namespace uavmot
