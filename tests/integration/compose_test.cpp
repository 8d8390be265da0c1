// Air and ground in containers: docker/compose.yaml with podman-compose, as CI runs it. The
// images are built here (docker/build_image.sh: the base image is rebuilt only when its package
// list changes, the uavmot image always, from build/bin), the air and ground containers run on
// separate networks, and the ground container's result folder ends up with the same results as
// `uavmot process` on the same sequence. Needs root (podman networks, debootstrap); skipped otherwise.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
using testing::read_file;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kDocker = build_paths::source_dir() + "/docker";
const std::string kProject = "uavmotcompose";
constexpr int kFrames = 80;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Runs argv to completion (or kills it at the deadline); returns the exit code, nullopt on timeout.
std::optional<int> run(const std::vector<std::string>& argv, const std::string& log, std::chrono::seconds timeout,
                       const std::map<std::string, std::string>& env = {}) {
  ChildProcess p(argv, log, env);
  return p.wait(timeout);
}

std::string output_of(const std::vector<std::string>& argv, const std::string& log) {
  run(argv, log, std::chrono::seconds(60));
  std::string text = read_file(log);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

class Compose : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root: podman networks and the base image's debootstrap";
    root_ = testing::fresh_dir("compose");
    env_ = {{"CONTAINERS_CONF", kDocker + "/containers.conf"}, {"SEQUENCE", root_ + "/paper"},
            {"RESULTS", root_ + "/results"}, {"UAVMOT_DOMAIN", "137"}};
    down();  // whatever a killed earlier run left
  }
  void TearDown() override {
    if (!root_.empty()) down();
  }
  std::vector<std::string> compose(std::vector<std::string> args) const {
    std::vector<std::string> argv = {"/usr/bin/podman-compose", "-p", kProject, "-f", kDocker + "/compose.yaml"};
    for (const auto& file : overlays_) argv.insert(argv.end(), {"-f", kDocker + "/" + file});
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
  }
  void down() const { run(compose({"down"}), root_ + "/down.log", std::chrono::seconds(120), env_); }
  std::string podman(const std::vector<std::string>& args, const std::string& name) const {
    std::vector<std::string> argv = {"/usr/bin/podman"};
    argv.insert(argv.end(), args.begin(), args.end());
    return output_of(argv, root_ + "/" + name + ".log");
  }

  void run_and_check();

  std::string root_;
  std::map<std::string, std::string> env_;
  std::vector<std::string> overlays_;  // compose files over compose.yaml, e.g. compose.security.yaml
};

TEST_F(Compose, AirAndGroundContainersOnSeparateNetworksDeliverTheResultsToTheGround) { run_and_check(); }

// The same with DDS Security on (tools/make_security.sh, mounted by compose.security.yaml and
// selected by qos_dir): the same results, and both containers had the material.
TEST_F(Compose, WithSecurityOnTheContainersDeliverTheSameResults) {
  const std::string security = root_ + "/security";
  ASSERT_EQ(run({"/bin/sh", build_paths::source_dir() + "/tools/make_security.sh", security}, root_ + "/make_security.log",
                std::chrono::seconds(60)),
            0)
      << read_file(root_ + "/make_security.log");
  env_["QOS_DIR"] = security;
  overlays_ = {"compose.security.yaml"};
  down();
  run_and_check();
  const std::string mounts = "{{range .Mounts}}{{.Destination}} {{end}}";
  for (const char* service : {"ground", "air"}) {
    const std::string container = kProject + "_" + service + "_" + "1";
    const std::string seen = podman({"inspect", "--format", mounts, container}, std::string(service) + "_mounts");
    EXPECT_NE(seen.find(security), std::string::npos) << service << ": " << seen;
    const std::string cmd = podman({"inspect", "--format", "{{.Config.Cmd}}", container}, std::string(service) + "_cmd");
    EXPECT_NE(cmd.find("qos_dir=" + security), std::string::npos) << service << ": " << cmd;
  }
}

void Compose::run_and_check() {
  for (const char* tool : {"/usr/bin/podman", "/usr/bin/podman-compose", "/usr/sbin/debootstrap", "/usr/sbin/runc"}) {
    ASSERT_TRUE(fs::exists(tool)) << tool << " is missing: tools/install_deps.sh installs it";
  }
  ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "11", "--frames", std::to_string(kFrames), "--out",
                    root_ + "/paper"},
                   root_ + "/sim.log");
  ASSERT_EQ(sim.wait(std::chrono::seconds(120)), 0) << sim.log();
  ChildProcess process({binary("uavmot-process"), root_ + "/paper", "--out", root_ + "/process", "--quiet"}, root_ + "/process.log");
  ASSERT_EQ(process.wait(std::chrono::seconds(240)), 0) << process.log();
  fs::create_directories(root_ + "/results");

  // Images: the base is reused when its package list is unchanged; the first build takes minutes.
  auto start = Clock::now();
  ASSERT_EQ(run({"/bin/sh", kDocker + "/build_image.sh", build_paths::binary_dir()}, root_ + "/build_image.log", std::chrono::seconds(1500), env_), 0)
      << read_file(root_ + "/build_image.log");
  const double build_s = seconds_since(start);

  start = Clock::now();
  ASSERT_EQ(run(compose({"up", "-d"}), root_ + "/up.log", std::chrono::seconds(120), env_), 0) << read_file(root_ + "/up.log");
  // Both containers end by themselves: the ground when its sink has every stream's end, the air
  // when its downlink passed the end on.
  for (const char* service : {"ground", "air"}) {
    const std::string container = kProject + "_" + service + "_1";
    const auto waited = run({"/usr/bin/podman", "wait", container}, root_ + "/wait_" + service + ".log", std::chrono::seconds(300));
    EXPECT_TRUE(waited.has_value()) << container << " still running after 300 s";
  }
  const double run_s = seconds_since(start);
  const std::string ground_log = podman({"logs", kProject + "_ground_1"}, "ground");
  const std::string air_log = podman({"logs", kProject + "_air_1"}, "air");
  EXPECT_EQ(podman({"inspect", "--format", "{{.State.ExitCode}}", kProject + "_ground_1"}, "ground_exit"), "0") << ground_log;
  EXPECT_EQ(podman({"inspect", "--format", "{{.State.ExitCode}}", kProject + "_air_1"}, "air_exit"), "0") << air_log;
  std::printf("[compose] images built in %.1f s, containers ran in %.1f s\n", build_s, run_s);

  // Separate networks: the ground is only on the downlink, the air on its own network and the downlink.
  const std::string networks = "{{range $name, $net := .NetworkSettings.Networks}}{{$name}} {{end}}";
  const std::string ground_networks = podman({"inspect", "--format", networks, kProject + "_ground_1"}, "ground_networks");
  const std::string air_networks = podman({"inspect", "--format", networks, kProject + "_air_1"}, "air_networks");
  EXPECT_EQ(ground_networks, kProject + "_downlink") << ground_networks;
  EXPECT_NE(air_networks.find(kProject + "_downlink"), std::string::npos) << air_networks;
  EXPECT_NE(air_networks.find(kProject + "_air_internal"), std::string::npos) << air_networks;

  // The ground container's results: the in-process run's, byte for byte.
  const std::string out = root_ + "/results", expected = root_ + "/process";
  ASSERT_FALSE(read_file(expected + "/tracks.txt").empty()) << "the in-process run found no tracks: nothing would be compared";
  for (const char* file : {"homographies.txt", "tracks.txt", "tracks_obb.csv", "regions.txt"}) {
    EXPECT_EQ(read_file(out + "/" + file), read_file(expected + "/" + file)) << file << "\n" << ground_log << air_log;
  }
}

}  // namespace
}  // namespace uavmot
