#include "uavmot/core/output_file.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "uavmot/core/durable_file.hpp"
#include "uavmot/core/error.hpp"
#include "uavmot/core/result_files.hpp"
#include "scratch_dir.hpp"

namespace uavmot {
namespace {

std::filesystem::path fresh_dir(const std::string& name) { return test_support::fresh_scratch_dir(name); }

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
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

// write_file_durably: the saved states of the tracker and of motion.
std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

TEST(WriteFileDurably, WritesTheBytes) {
  const auto path = fresh_dir("uavmot_durable_file_write") / "state.cdr";
  const std::string text("binary\0bytes\n", 13);
  write_file_durably(path.string(), bytes_of(text));
  EXPECT_EQ(read_all(path), text);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  write_file_durably(path.string(), {});
  EXPECT_EQ(std::filesystem::file_size(path), 0u);
}

TEST(WriteFileDurably, ReplacesTheFileByRenameKeepingTheOldOneUntilThen) {
  const auto dir = fresh_dir("uavmot_durable_file_replace");
  const auto path = dir / "state.cdr";
  write_file_durably(path.string(), bytes_of("a longer first version\n"));
  // A second name for the first version: the new content comes in as a new file renamed over the
  // name, so the first file is never rewritten in place (a reader of it sees it whole).
  std::filesystem::create_hard_link(path, dir / "first.cdr");
  ASSERT_EQ(std::filesystem::hard_link_count(path), 2u);
  write_file_durably(path.string(), bytes_of("second\n"));
  EXPECT_EQ(read_all(path), "second\n");
  EXPECT_EQ(std::filesystem::hard_link_count(path), 1u);
  EXPECT_EQ(read_all(dir / "first.cdr"), "a longer first version\n");
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
}

// /dev/full fails every write with ENOSPC, as a full disk does: the file keeps its last content.
TEST(WriteFileDurably, AFailedWriteLeavesThePreviousContentAndNamesTheFile) {
  ASSERT_TRUE(std::filesystem::exists("/dev/full"));
  const auto dir = fresh_dir("uavmot_durable_file_full");
  const auto path = dir / "state.cdr";
  write_file_durably(path.string(), bytes_of("previous\n"));
  std::filesystem::create_symlink("/dev/full", path.string() + ".tmp");
  const std::string message = message_of([&] { write_file_durably(path.string(), bytes_of("next\n")); });
  EXPECT_NE(message.find("'" + path.string() + ".tmp'"), std::string::npos) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  EXPECT_EQ(read_all(path), "previous\n");
}

TEST(WriteFileDurably, AMissingFolderIsAnOutputErrorNamingTheFile) {
  const auto path = fresh_dir("uavmot_durable_file_missing") / "no_such_folder" / "state.cdr";
  const std::string message = message_of([&] { write_file_durably(path.string(), bytes_of("x")); });
  EXPECT_NE(message.find("'" + path.string() + ".tmp'"), std::string::npos) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(path.parent_path()));
}

}  // namespace
}  // namespace uavmot
