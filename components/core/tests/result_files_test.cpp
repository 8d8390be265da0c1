#include "uavmot/core/result_files.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "scratch_dir.hpp"

namespace uavmot {
namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ResultFiles, WritesMotChallengeTracksOfConfirmedTracksOnly) {
  const auto dir = test_support::scratch_path("result_files");
  std::filesystem::remove_all(dir);
  {
    ResultFilesWriter writer({dir.string(), 25.0, 0.5, true, true});
    MotionEstimate motion;
    motion.frame_index = 1;
    motion.features.push_back({7, {10, 20}, {0.5, 0}, 0.05, 3, true});
    writer.write_motion(motion);
    TrackList tracks;
    tracks.frame_index = 1;
    Track confirmed;
    confirmed.id = 1;
    confirmed.state = TrackState::Confirmed;
    confirmed.box = {100, 50, 2, 10, 90};
    confirmed.velocity = {1.0, 0.0};
    Track tentative = confirmed;
    tentative.id = 2;
    tentative.state = TrackState::Tentative;
    tracks.tracks = {confirmed, tentative};
    writer.write_tracks(tracks);
    writer.close({});
  }
  EXPECT_EQ(read_all(dir / "tracks.txt"), "1,1,99.000,45.000,2.000,10.000,1.000,-1,-1,-1\n");
  EXPECT_EQ(read_all(dir / "homographies.txt"), "1,1,0,0,0,1,0,0,0,1\n");
  EXPECT_EQ(read_all(dir / "features.csv"), "frame,feature_id,x,y,vx,vy,moving\n1,7,10.000,20.000,0.5000,0.0000,1\n");
  const std::string obb = read_all(dir / "tracks_obb.csv");
  // 1 px/frame * 0.5 m/px * 25 fps = 12.5 m/s = 45 km/h
  EXPECT_NE(obb.find("1,1,confirmed,100.000,50.000,2.000,10.000,90.000,1.0000,0.0000,50.000,25.000,1.000,5.000,12.500,45.00"),
            std::string::npos) << obb;
  EXPECT_NE(read_all(dir / "summary.json").find("\"confirmed_tracks\": 1"), std::string::npos);
}

// With the input's ground geometry, tracks_obb.csv gets each box centre's lat,lon (empty where the
// frame has no mapping), and summary.json says where the GSD came from and what metadata was read.
TEST(ResultFiles, LatLonColumnsAndMetadataSummary) {
  const auto dir = test_support::scratch_path("result_files_latlon");
  std::filesystem::remove_all(dir);
  {
    ResultFilesOptions options{dir.string(), 25.0, 0.0, false, false};
    ResultFilesWriter writer(options, [](int64_t frame, double x, double y) -> std::optional<std::array<double, 2>> {
      if (frame != 1) return std::nullopt;
      return std::array<double, 2>{38.0 + y * 1e-6, -77.0 + x * 1e-6};
    });
    Track t;
    t.id = 3;
    t.state = TrackState::Confirmed;
    t.box = {100, 50, 2, 10, 90};
    for (int64_t frame : {1, 2}) writer.write_tracks({"uav1", frame, 0, {t}});
    RunSummary summary;
    summary.gsd_source = "klv";
    summary.metadata = MetadataSummary{48, "EG 0104", 0, 48};
    writer.close(summary);
  }
  const std::string obb = read_all(dir / "tracks_obb.csv");
  EXPECT_EQ(obb,
            "frame,id,state,cx,cy,width,length,angle_deg,vx,vy,lat,lon\n"
            "1,3,confirmed,100.000,50.000,2.000,10.000,90.000,0.0000,0.0000,38.0000500,-76.9999000\n"
            "2,3,confirmed,100.000,50.000,2.000,10.000,90.000,0.0000,0.0000,,\n");
  const std::string summary = read_all(dir / "summary.json");
  EXPECT_NE(summary.find("\"gsd_source\": \"klv\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"standard\": \"EG 0104\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"frames_with_geometry\": 48"), std::string::npos) << summary;
}

TEST(ResultFiles, UnwritableFolderIsAnInputError) {
  EXPECT_THROW(ResultFilesWriter({"/proc/uavmot-cannot-write-here", 25.0, 0.0, true, true}), InputError);
}

}  // namespace
}  // namespace uavmot
