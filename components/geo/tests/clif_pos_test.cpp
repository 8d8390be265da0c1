#include "uavmot/geo/clif_pos.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"

namespace uavmot::geo {
namespace {

std::vector<ClifPosRecord> read_all() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(build_paths::data_dir() + "/clif2007/pos")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<ClifPosRecord> records;
  for (const auto& f : files) records.push_back(read_clif_pos_file(f));
  return records;
}

TEST(ClifPos, FirstRecord) {
  const ClifPosRecord r = read_clif_pos_file(build_paths::data_dir() + "/clif2007/pos/000000-100006.txt");
  EXPECT_FALSE(r.source_name);
  EXPECT_DOUBLE_EQ(r.yaw_deg, 344.1953273632474861);
  EXPECT_DOUBLE_EQ(r.latitude_deg, 40.0048617231066572);  // Columbus, Ohio
  EXPECT_DOUBLE_EQ(r.longitude_deg, -82.9920615234223931);
  EXPECT_DOUBLE_EQ(r.altitude_ft, 9219.8927508235574351);
  EXPECT_NEAR(r.altitude_m(), 2810.2, 0.1);
  EXPECT_EQ(r.gps_week, 1451);  // the week from 28 October 2007
  EXPECT_DOUBLE_EQ(r.north_velocity_mps, 51.1580298949112660);
  EXPECT_EQ(r.imu_status, 3);
  EXPECT_EQ(r.local_adjustment, -4);
  EXPECT_EQ(r.dst_flags, 1);
}

// The identification of the fields, checked on the data: the velocities match the motion between
// consecutive positions, and yaw follows the direction of travel (within the crab angle).
TEST(ClifPos, VelocitiesMatchThePositions) {
  const auto records = read_all();
  ASSERT_EQ(records.size(), 250u);
  for (std::size_t i = 0; i + 1 < records.size(); i += 10) {
    const ClifPosRecord& a = records[i];
    const ClifPosRecord& b = records[i + 1];
    const double dt = b.gps_seconds_of_week - a.gps_seconds_of_week;
    ASSERT_GT(dt, 0.3) << i;
    ASSERT_LT(dt, 2.0) << i;  // 0.63 s a frame, more where the set skips one
    const LocalTangentPlane plane(a.position());
    const cv::Point2d d = plane.to_east_north(b.position());
    EXPECT_NEAR(d.y / dt, (a.north_velocity_mps + b.north_velocity_mps) / 2.0, 3.0) << i;
    EXPECT_NEAR(d.x / dt, (a.east_velocity_mps + b.east_velocity_mps) / 2.0, 3.0) << i;
    const double track_deg = std::atan2(a.east_velocity_mps, a.north_velocity_mps) * 180.0 / std::numbers::pi;
    double diff = std::fmod(a.yaw_deg - track_deg + 540.0, 360.0) - 180.0;
    EXPECT_LT(std::abs(diff), 25.0) << i;
  }
}

TEST(ClifPos, FifteenFieldsWithASourceName) {
  const ClifPosRecord r = parse_clif_pos_line("cam0, 1, 2, 3, 40, -83, 9000, 100.5, 1451, 1, 2, 3, 3, -4, 1", "x");
  EXPECT_EQ(r.source_name, "cam0");
  EXPECT_DOUBLE_EQ(r.yaw_deg, 1.0);
  EXPECT_DOUBLE_EQ(r.gps_seconds_of_week, 100.5);
}

TEST(ClifPos, MalformedLinesAreInputErrors) {
  EXPECT_THROW(parse_clif_pos_line("", "a"), InputError);
  EXPECT_THROW(parse_clif_pos_line("1,2,3", "a"), InputError);
  EXPECT_THROW(parse_clif_pos_line("1,2,3,40,-83,9000,100,1451.5,1,2,3,3,-4,1", "a"), InputError);  // week
  EXPECT_THROW(parse_clif_pos_line("1,2,3,95,-83,9000,100,1451,1,2,3,3,-4,1", "a"), InputError);    // latitude
  EXPECT_THROW(parse_clif_pos_line("1,2,x,40,-83,9000,100,1451,1,2,3,3,-4,1", "a"), InputError);
  try {
    parse_clif_pos_line("1,2,nan,40,-83,9000,100,1451,1,2,3,3,-4,1", "f.txt:1");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.txt:1: roll"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_clif_pos_file("/nonexistent.txt"), InputError);
}

}  // namespace
}  // namespace uavmot::geo
