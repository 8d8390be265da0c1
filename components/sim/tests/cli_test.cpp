// The uavmot-sim process: its output folder, its help, and clear failures on bad input.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"

namespace {
namespace fs = std::filesystem;

struct ProcessResult {
  int code = -1;
  std::string output;  // stdout and stderr
};

ProcessResult run(const std::string& args) {
  const fs::path log = fs::temp_directory_path() / ("uavmot_sim_cli_" + std::to_string(::getpid()) + ".log");
  const std::string cmd = uavmot::build_paths::binary_dir() + "/bin/uavmot-sim " + args + " >" + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  fs::remove(log);
  return r;
}

class SimCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("uavmot_sim_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

TEST_F(SimCli, WritesAnMotChallengeSequence) {
  const std::string yaml = write("s.yaml", "preset: paper\nframes: 3\ncamera:\n  width: 320\n  height: 240\n");
  const ProcessResult r = run("--scenario " + yaml + " --seed 4 --out " + (dir_ / "seq").string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"seqinfo.ini", "meta.json", "video.mp4", "img1/000001.jpg", "img1/000003.jpg", "gt/gt.txt",
                        "gt/all_objects.txt", "gt/gt_obb.csv", "gt/homographies.txt", "gt/masks/000003.png"})
    EXPECT_TRUE(fs::exists(dir_ / "seq" / f)) << f;
  EXPECT_FALSE(fs::exists(dir_ / "seq" / "img1" / "000004.jpg"));
  std::ifstream ini(dir_ / "seq" / "seqinfo.ini");
  std::stringstream text;
  text << ini.rdbuf();
  for (const char* line : {"imDir=img1", "seqLength=3", "imWidth=320", "imHeight=240", "imExt=.jpg", "gsd=0.35", "frameRate=25"})
    EXPECT_NE(text.str().find(line), std::string::npos) << line;
  EXPECT_NE(r.output.find("frame 3/3"), std::string::npos) << "progress on stderr";
}

TEST_F(SimCli, FramesOverrideAndSameSeedSameBytes) {
  const std::string a = (dir_ / "a" / "seq").string(), b = (dir_ / "b" / "seq").string();
  const std::string common = "--scenario " + write("t.yaml", "camera:\n  width: 256\n  height: 192\n");
  ASSERT_EQ(run(common + " --seed 9 --frames 2 --out " + a + " -q").code, 0);
  ASSERT_EQ(run(common + " --seed 9 --frames 2 --out " + b + " -q").code, 0);
  for (const char* f : {"img1/000001.jpg", "img1/000002.jpg", "gt/gt.txt", "gt/all_objects.txt", "gt/gt_obb.csv",
                        "gt/homographies.txt", "gt/masks/000002.png", "meta.json", "seqinfo.ini", "video.mp4"}) {
    std::ifstream fa(fs::path(a) / f, std::ios::binary), fb(fs::path(b) / f, std::ios::binary);
    std::stringstream sa, sb;
    sa << fa.rdbuf();
    sb << fb.rdbuf();
    EXPECT_FALSE(sa.str().empty()) << f;
    EXPECT_EQ(sa.str(), sb.str()) << f;
  }
  EXPECT_FALSE(fs::exists(fs::path(a) / "img1" / "000003.jpg"));
}

TEST_F(SimCli, HelpAndDescribe) {
  const ProcessResult help = run("--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.output.find("--preset"), std::string::npos);
  const ProcessResult describe = run("--describe");
  EXPECT_EQ(describe.code, 0);
  EXPECT_EQ(std::count(describe.output.begin(), describe.output.end(), '\n'), 1);
}

TEST_F(SimCli, BadInputFailsClearly) {
  ProcessResult r = run("--preset nosuch --out " + (dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("nosuch"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fastcam"), std::string::npos) << "lists the presets: " << r.output;

  r = run("--scenario " + write("bad.yaml", "camera:\n  widht: 3\n") + " --out " + (dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("widht"), std::string::npos) << r.output;

  r = run("--scenario " + write("syntax.yaml", "camera: [1, 2\n") + " --out " + (dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("syntax.yaml"), std::string::npos) << r.output;

  r = run("--scenario " + (dir_ / "missing.yaml").string() + " --out " + (dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("missing.yaml"), std::string::npos) << r.output;

  const std::string file = write("plainfile", "x");
  r = run("--preset paper --frames 1 --out " + file + "/sub");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("plainfile"), std::string::npos) << r.output;

  r = run("--preset paper");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;

  r = run("--preset paper --frames 0 --out " + (dir_ / "x").string());
  EXPECT_NE(r.code, 0);
}

}  // namespace
