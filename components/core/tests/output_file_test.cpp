#include "uavmot/core/output_file.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "uavmot/core/error.hpp"
#include "uavmot/core/result_files.hpp"

namespace uavmot {
namespace {

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  return "(no OutputError)";
}

TEST(OutputFile, WritesRecordsAndCountsTheirBytes) {
  const auto path = fresh_dir("uavmot_output_file_test") / "a.txt";
  OutputFile file(path.string());
  file.append("1,2\n");
  file.append("");
  file.append("3,4\n5,6\n");
  EXPECT_EQ(file.bytes(), 12u);
  file.close();
  file.close();  // closing twice does nothing
  EXPECT_EQ(read_all(path), "1,2\n3,4\n5,6\n");
}

TEST(OutputFile, UnopenablePathIsAnInputError) {
  EXPECT_THROW(OutputFile("/proc/uavmot-cannot-write-here/a.txt"), InputError);
}

// /dev/full fails every write with ENOSPC, as a full disk does.
TEST(OutputFile, FullDeviceIsAnOutputErrorNamingTheFileAndTheReason) {
  ASSERT_TRUE(std::filesystem::exists("/dev/full"));
  OutputFile file("/dev/full");
  const std::string message = message_of([&] { file.append("1,2\n"); });
  EXPECT_NE(message.find("'/dev/full'"), std::string::npos) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  EXPECT_EQ(file.bytes(), 0u);
}

// The result writer on a full disk: tracks.txt is /dev/full (a symlink the writer opens through).
TEST(ResultFiles, FullDiskThrowsOutputErrorNamingTheFile) {
  const auto dir = fresh_dir("uavmot_result_files_full_test");
  std::filesystem::create_symlink("/dev/full", dir / "tracks.txt");
  ResultFilesWriter writer({dir.string(), 25.0, 0.0, false, false});
  TrackList tracks;
  tracks.frame_index = 1;
  Track t;
  t.id = 1;
  t.state = TrackState::Confirmed;
  t.box = {100, 50, 2, 10, 90};
  tracks.tracks = {t};
  const std::string message = message_of([&] { writer.write_tracks(tracks); });
  EXPECT_NE(message.find("tracks.txt"), std::string::npos) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
}

}  // namespace
}  // namespace uavmot
