// `uavmot process` on an MPEG-TS with KLV (data/aphill/aphill_short.ts): the GSD comes from the
// flight metadata and is said in the log and summary.json, and tracks.geojson is written and parses.
// The geo library's own reading of the clip is the reference.

#include <filesystem>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/geo/flight_metadata.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
using testing::read_file;

const std::string kClip = build_paths::data_dir() + "/aphill/aphill_short.ts";

TEST(GeoProcess, AphillGsdFromKlvInLogAndSummaryAndTracksGeojson) {
  const std::string root = testing::fresh_dir("geo_process");
  ChildProcess process({binary("uavmot-process"), kClip, "--out", root + "/out", "--quiet"}, root + "/process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(300)), 0) << process.log();

  // The reference: the library's median over the clip's 48 decoded frames (29.97 frames/s).
  const geo::FlightMetadata flight = geo::read_flight_metadata(kClip, {720, 480}, 30000.0 / 1001.0, 48);
  ASSERT_TRUE(flight.summary.median_gsd_m_per_px);
  const double expected = *flight.summary.median_gsd_m_per_px;
  EXPECT_NEAR(expected, 0.0484, 0.0005);

  std::smatch m;
  const std::string log = process.log();
  ASSERT_TRUE(std::regex_search(log, m, std::regex(R"(GSD ([0-9.]+) m/px from KLV metadata \(48 packets, EG 0104)"))) << log;
  EXPECT_NEAR(std::stod(m[1].str()), expected, 0.0006);  // printed with 3 decimals
  EXPECT_EQ(log.find("no GSD known"), std::string::npos) << log;

  const auto summary = nlohmann::json::parse(read_file(root + "/out/summary.json"));
  EXPECT_EQ(summary.at("gsd_source"), "klv");
  EXPECT_NEAR(summary.at("gsd_m").get<double>(), expected, 0.001);
  EXPECT_EQ(summary.at("metadata").at("packets"), 48);
  EXPECT_EQ(summary.at("metadata").at("standard"), "EG 0104");
  EXPECT_EQ(summary.at("metadata").at("bad_checksums"), 0);
  EXPECT_GE(summary.at("metadata").at("frames_with_geometry").get<int>(), 48);

  ASSERT_TRUE(std::filesystem::exists(root + "/out/tracks.geojson"));
  const auto geojson = nlohmann::json::parse(read_file(root + "/out/tracks.geojson"));
  EXPECT_EQ(geojson.at("type"), "FeatureCollection");
  ASSERT_TRUE(geojson.at("features").is_array());
  for (const auto& f : geojson.at("features")) {
    EXPECT_EQ(f.at("geometry").at("type"), "LineString");
    EXPECT_GE(f.at("properties").at("mean_speed_mps").get<double>(), 0.0);
  }
  // tracks_obb.csv names the ground position of each box.
  const std::string obb = read_file(root + "/out/tracks_obb.csv");
  EXPECT_EQ(obb.substr(0, obb.find('\n')),
            "frame,id,state,cx,cy,width,length,angle_deg,vx,vy,cx_m,cy_m,width_m,length_m,speed_mps,speed_kmh,lat,lon");
}

// --gsd overrides the metadata; the metadata is still read and the map still written.
TEST(GeoProcess, GsdFlagOverridesKlv) {
  const std::string root = testing::fresh_dir("geo_process_flag");
  ChildProcess process({binary("uavmot-process"), kClip, "--out", root + "/out", "--quiet", "--gsd", "0.1", "--count", "10"},
                       root + "/process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(300)), 0) << process.log();
  EXPECT_NE(process.log().find("GSD 0.1 m/px from --gsd"), std::string::npos) << process.log();
  const auto summary = nlohmann::json::parse(read_file(root + "/out/summary.json"));
  EXPECT_EQ(summary.at("gsd_source"), "flag");
  EXPECT_DOUBLE_EQ(summary.at("gsd_m").get<double>(), 0.1);
  EXPECT_EQ(summary.at("metadata").at("packets"), 48);
  EXPECT_TRUE(std::filesystem::exists(root + "/out/tracks.geojson"));
}

// No GSD from anywhere: one warning that names the default, and gsd_source "default".
TEST(GeoProcess, NoGsdKnownWarnsOnceWithTheDefault) {
  const std::string root = testing::fresh_dir("geo_process_default");
  ChildProcess process({binary("uavmot-process"), build_paths::data_dir() + "/aphill/aphill_240_1fps_crf32.mp4", "--out",
                        root + "/out", "--quiet", "--count", "5"},
                       root + "/process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(300)), 0) << process.log();
  const std::string log = process.log();
  const auto first = log.find("no GSD known");
  ASSERT_NE(first, std::string::npos) << log;
  EXPECT_EQ(log.find("no GSD known", first + 1), std::string::npos) << log;
  EXPECT_NE(log.find("using the default 0.35 m/px"), std::string::npos) << log;
  const auto summary = nlohmann::json::parse(read_file(root + "/out/summary.json"));
  EXPECT_EQ(summary.at("gsd_source"), "default");
  EXPECT_FALSE(summary.contains("metadata"));
  EXPECT_FALSE(std::filesystem::exists(root + "/out/tracks.geojson"));
}

// A CLIF folder: the frame rate from the POS GPS times (median step 0.630 s).
TEST(GeoProcess, ClifFrameRateFromPosRecords) {
  const std::string root = testing::fresh_dir("geo_process_clif");
  ChildProcess process({binary("uavmot-process"), build_paths::data_dir() + "/clif2007/jpg", "--out", root + "/out", "--quiet",
                        "--count", "3"},
                       root + "/process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(600)), 0) << process.log();
  const std::string log = process.log();
  EXPECT_NE(log.find("frame rate 1.587 fps from the CLIF POS GPS times"), std::string::npos) << log;
  EXPECT_NE(log.find("CLIF POS records hold no focal length"), std::string::npos) << log;
}

}  // namespace
}  // namespace uavmot
