#include "uavmot/core/segmentation_method.hpp"

#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"

namespace uavmot {
namespace {

TEST(SegmentationMethod, EveryMethodParsesFromItsName) {
  for (SegmentationMethod m : kSegmentationMethods) EXPECT_EQ(parse_segmentation_method(to_string(m)), m);
  EXPECT_EQ(segmentation_method_names().size(), kSegmentationMethods.size());
}

TEST(SegmentationMethod, ListPositionIsTheWireNumber) {
  for (size_t i = 0; i < kSegmentationMethods.size(); ++i) {
    EXPECT_EQ(static_cast<size_t>(kSegmentationMethods[i]), i);
    EXPECT_TRUE(is_segmentation_method(i));
  }
  EXPECT_FALSE(is_segmentation_method(kSegmentationMethods.size()));
  // The paper's methods keep their numbers (recordings and the downlink carry them).
  EXPECT_EQ(static_cast<int>(SegmentationMethod::Clustering), 0);
  EXPECT_EQ(static_cast<int>(SegmentationMethod::Fusion), 4);
}

TEST(SegmentationMethod, UnknownNameNamesTheChoices) {
  try {
    parse_segmentation_method("sobol");
    FAIL() << "no throw";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("sobol"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find(segmentation_method_choices()), std::string::npos);
  }
  EXPECT_EQ(segmentation_method_choices().rfind("clustering, korn", 0), 0u);
}

}  // namespace
}  // namespace uavmot
