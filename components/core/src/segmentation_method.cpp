#include "uavmot/core/segmentation_method.hpp"

#include "uavmot/core/error.hpp"

namespace uavmot {

const char* to_string(SegmentationMethod method) {
  switch (method) {
#define UAVMOT_METHOD_CASE(enumerator, name) \
  case SegmentationMethod::enumerator: return name;
    UAVMOT_SEGMENTATION_METHODS(UAVMOT_METHOD_CASE)
#undef UAVMOT_METHOD_CASE
  }
  return "unknown";
}

SegmentationMethod parse_segmentation_method(const std::string& name) {
  for (SegmentationMethod m : kSegmentationMethods) {
    if (name == to_string(m)) return m;
  }
  throw InvalidArgument("unknown segmentation method '" + name + "' (expected " + segmentation_method_choices() + ")");
}

std::vector<std::string> segmentation_method_names() {
  std::vector<std::string> names;
  for (SegmentationMethod m : kSegmentationMethods) names.emplace_back(to_string(m));
  return names;
}

std::string segmentation_method_choices() {
  std::string text;
  for (size_t i = 0; i < kSegmentationMethods.size(); ++i) {
    if (i > 0) text += i + 1 == kSegmentationMethods.size() ? " or " : ", ";
    text += to_string(kSegmentationMethods[i]);
  }
  return text;
}

bool is_segmentation_method(uint64_t value) { return value < kSegmentationMethods.size(); }

}  // namespace uavmot
