#include "uavmot/dds/health_partitions.hpp"

#include <gtest/gtest.h>

namespace uavmot::dds {
namespace {

TEST(HealthPartitions, AReportCountsOnlyFromItsComponentsOwnPartition) {
  for (const auto& c : health_components()) EXPECT_TRUE(health_report_trusted(health_partition(c), c)) << c;
  EXPECT_FALSE(health_report_trusted(health_partition("sink"), "motion"));
  EXPECT_FALSE(health_report_trusted(health_partition("motion"), "sink"));
  EXPECT_FALSE(health_report_trusted("", "motion"));
  EXPECT_FALSE(health_report_trusted("*", "motion"));
}

TEST(HealthPartitions, TheDownlinkPassesOnTheAirComponentsOnly) {
  for (const char* c : {"source", "motion", "segmentation", "tracking"}) EXPECT_TRUE(health_report_trusted("downlink", c)) << c;
  EXPECT_FALSE(health_report_trusted("downlink", "sink"));
  EXPECT_FALSE(health_report_trusted("downlink", "view"));
}

}  // namespace
}  // namespace uavmot::dds
