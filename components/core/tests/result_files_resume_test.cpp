// A run whose writer died mid-frame is continued (ResultFilesOptions::resume): the files keep their
// whole frames, the torn frame is cut, and writing on from the resume point gives the files of an
// uninterrupted run, byte for byte.

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "uavmot/core/result_files.hpp"
#include "scratch_dir.hpp"

namespace uavmot {
namespace {
namespace fs = std::filesystem;

const char* const kFiles[] = {"tracks.txt", "tracks_obb.csv", "homographies.txt", "features.csv", "clusters.txt", "regions.txt"};

std::string read_all(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh(const std::string& name) {
  const fs::path dir = test_support::scratch_path("resume_" + name);
  fs::remove_all(dir);
  return dir;
}

MotionEstimate motion(int64_t k) {
  MotionEstimate m;
  m.frame_index = k;
  m.homography = k == 1 ? Homography::eye() : Homography(1, 0, 0.5 * static_cast<double>(k), 0, 1, -1, 0, 0, 1);
  m.quality.valid = k > 1;
  m.features = {{1, {10.0 + static_cast<double>(k), 20}, {0.5, 0}, 0.05, 3, true}, {2, {40, 30}, {0, 0}, 0.01, 9, false}};
  return m;
}

SegmentationResult segmentation(int64_t k) {
  SegmentationResult s;
  s.frame_index = k;
  if (k % 3 != 0) {  // some frames without regions or clusters, as on a real sequence
    s.clusters = {{1, {11.0 + static_cast<double>(k), 20, 4, 10, 0}, {0.5, 0}, {1}}};
    s.regions = {{{11.0 + static_cast<double>(k), 20, 4, 10, 0}, SegmentationMethod::Fusion, 0.9, 1}};
  }
  return s;
}

TrackList tracks(int64_t k) {
  TrackList t;
  t.frame_index = k;
  Track a;
  a.id = 1;
  a.state = k >= 3 ? TrackState::Confirmed : TrackState::Tentative;
  a.box = {11.0 + static_cast<double>(k), 20, 4, 10, 0};
  a.velocity = {0.5, 0};
  Track b = a;
  b.id = 2;
  b.state = TrackState::Confirmed;
  b.box.cy = 60;
  t.tracks = {a};
  if (k >= 2 && k <= 5) t.tracks.push_back(b);
  return t;
}

ResultFilesOptions options(const fs::path& dir, bool resume) {
  ResultFilesOptions o{dir.string(), 25.0, 0.5, true, true};
  o.resume = resume;
  return o;
}

void write_frames(ResultFilesWriter& writer, int64_t from, int64_t to, const ResumePoint& skip = {}) {
  for (int64_t k = from; k <= to; ++k) {
    if (k > skip.motion_frame) writer.write_motion(motion(k));
    if (k > skip.segmentation_frame) writer.write_segmentation(segmentation(k));
    if (k > skip.tracks_frame) writer.write_tracks(tracks(k));
  }
}

void append(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::app) << text; }

TEST(ResultFilesResume, TornFrameIsCutAndTheContinuedRunEqualsAnUninterruptedOne) {
  const fs::path whole = fresh("whole"), torn = fresh("torn");
  {
    ResultFilesWriter writer(options(whole, false));
    write_frames(writer, 1, 8);
    writer.close({});
  }
  {
    ResultFilesWriter writer(options(torn, false));
    write_frames(writer, 1, 4);
    // Dies here: files stay open and no summary.json is written.
  }
  // ... in the middle of frame 5: features of 5 without its homography, clusters without regions,
  // tracks.txt without tracks_obb.csv, and a line cut short.
  append(torn / "features.csv", "5,1,15.000,20.000,0.5000,0.0000,1\n");
  append(torn / "clusters.txt", "5,-1,14.000,15.000,4.000,10.000,1.000,-1,-1,-1\n");
  append(torn / "tracks.txt", "5,1,14.000,15.000,4.000,10.000,1.000,-1,-1,-1\n5,2,14.0");
  {
    ResultFilesWriter writer(options(torn, true));
    EXPECT_EQ(writer.resumed_at().motion_frame, 4);
    EXPECT_EQ(writer.resumed_at().segmentation_frame, 4);
    EXPECT_EQ(writer.resumed_at().tracks_frame, 4);
    EXPECT_EQ(writer.frames_written(), 4);
    // Frames come again from an earlier one (a writer's history): those written are skipped.
    write_frames(writer, 2, 8, writer.resumed_at());
    writer.close({});
  }
  for (const char* name : kFiles) EXPECT_EQ(read_all(torn / name), read_all(whole / name)) << name;
  const std::string summary = read_all(torn / "summary.json");
  EXPECT_NE(summary.find("\"frames\": 8"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"valid_homographies\": 7"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"confirmed_tracks\": 2"), std::string::npos) << summary;
}

// A segmentation frame without regions leaves no line: the resume point is the last frame with
// one, and the frames after it are written again (their clusters were cut with them).
TEST(ResultFilesResume, FramesWithoutLinesAreWrittenAgainFromTheLastMarkedFrame) {
  const fs::path whole = fresh("whole_gap"), torn = fresh("torn_gap");
  {
    ResultFilesWriter writer(options(whole, false));
    write_frames(writer, 1, 7);
    writer.close({});
  }
  {
    ResultFilesWriter writer(options(torn, false));
    write_frames(writer, 1, 6);  // frame 6 has no regions
  }
  ResultFilesWriter writer(options(torn, true));
  EXPECT_EQ(writer.resumed_at().segmentation_frame, 5);
  EXPECT_EQ(writer.resumed_at().motion_frame, 6);
  write_frames(writer, 1, 7, writer.resumed_at());
  writer.close({});
  for (const char* name : kFiles) EXPECT_EQ(read_all(torn / name), read_all(whole / name)) << name;
}

// The downlink sink writes a frame's regions, tracks and motion together, homographies.txt last:
// every file is cut to its last frame.
TEST(ResultFilesResume, WholeFramesAreCutToTheLastHomography) {
  const fs::path dir = fresh("whole_frames");
  {
    ResultFilesWriter writer(options(dir, false));
    write_frames(writer, 1, 3);
    writer.write_segmentation(segmentation(4));
    writer.write_tracks(tracks(4));  // then died before frame 4's motion
  }
  ResultFilesOptions o = options(dir, true);
  o.resume_whole_frames = true;
  ResultFilesWriter writer(o);
  EXPECT_EQ(writer.resumed_at().motion_frame, 3);
  EXPECT_EQ(writer.resumed_at().segmentation_frame, 3);
  EXPECT_EQ(writer.resumed_at().tracks_frame, 3);
  writer.close({});
  for (const char* name : {"tracks.txt", "tracks_obb.csv", "regions.txt"}) {
    const std::string text = "\n" + read_all(dir / name);
    EXPECT_EQ(text.find("\n4,"), std::string::npos) << name << text;
    EXPECT_NE(text.find("\n2,"), std::string::npos) << name << text;
  }
}

TEST(ResultFilesResume, FinishedRunIsNotContinued) {
  const fs::path dir = fresh("finished");
  {
    ResultFilesWriter writer(options(dir, false));
    write_frames(writer, 1, 2);
    writer.close({});
  }
  try {
    ResultFilesWriter writer(options(dir, true));
    FAIL() << "a finished run was continued";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has ended (summary.json)"), std::string::npos) << e.what();
  }
  EXPECT_NE(read_all(dir / "tracks.txt"), "") << "nothing was cut";
}

TEST(ResultFilesResume, FilesOfOtherColumnsOrNotResultsAreRefused) {
  const fs::path dir = fresh("other_columns");
  {
    ResultFilesWriter writer(options(dir, false));  // GSD 0.5: metric columns
    write_frames(writer, 1, 2);
  }
  ResultFilesOptions no_gsd = options(dir, true);
  no_gsd.gsd_m = 0.0;
  EXPECT_THROW(ResultFilesWriter{no_gsd}, InputError);
  std::ofstream(dir / "homographies.txt", std::ios::app) << "not a result line\n";
  try {
    ResultFilesWriter writer(options(dir, true));
    FAIL() << "a foreign file was continued";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3 is not a result line"), std::string::npos) << e.what();
  }
}

TEST(ResultFilesResume, EmptyFolderStartsANewRun) {
  const fs::path dir = fresh("empty");
  ResultFilesWriter writer(options(dir, true));
  EXPECT_EQ(writer.resumed_at().motion_frame, 0);
  write_frames(writer, 1, 2);
  writer.close({});
  EXPECT_EQ(read_all(dir / "tracks_obb.csv").rfind("frame,id,state", 0), 0u);
}

}  // namespace
}  // namespace uavmot
