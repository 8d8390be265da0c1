#include "uavmot/launch/profile.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "uavmot/build_paths/build_paths.hpp"
#include "uavmot/core/error.hpp"
#include "scratch_dir.hpp"

namespace uavmot::launch {
namespace {

std::string write_profile(const std::string& name, const std::string& text) {
  const auto path = test_support::scratch_path(name);
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchProfile, ShippedProfilesLoadAndResolve) {
  for (const char* name : {"local.yaml", "air.yaml", "ground.yaml"}) {
    const auto profile = load_profile(build_paths::source_dir() + "/bringup/" + name);
    EXPECT_FALSE(profile.processes.empty()) << name;
    const auto resolved = resolve(profile, {{"input", "seq"}, {"out", "o"}, {"gsd", "0.35"}, {"fps", "25"}, {"profile_dir", "."}, {"run_dir", "/tmp/r"}});
    for (const auto& p : resolved.processes) {
      for (const auto& a : p.args) EXPECT_EQ(a.find("${"), std::string::npos) << name << " " << p.name << " " << a;
    }
  }
}

TEST(LaunchProfile, ReadsEveryField) {
  const auto file = write_profile("uavmot_profile_fields.yaml", R"(
description: test
variables: {domain: "3", hang: "2.5"}
common_args: [--domain, "${domain}"]
processes:
  - name: a
    command: source
    args: ["${input}"]
    env: {X: "${domain}"}
    hang_timeout: "${hang}"
    respawn: true
    respawn_args: [--resume, "${domain}"]
    respawn_delay: 0.5
    max_respawns: 2
    stop_on_failure: true
  - name: b
    command: sink
    required: true
    common_args: false
)");
  const auto profile = resolve(load_profile(file), {{"input", "seq"}});
  ASSERT_EQ(profile.processes.size(), 2u);
  EXPECT_EQ(profile.common_args, (std::vector<std::string>{"--domain", "3"}));
  EXPECT_EQ(profile.processes[0].args, std::vector<std::string>{"seq"});
  EXPECT_EQ(profile.processes[0].env.at("X"), "3");
  EXPECT_TRUE(profile.processes[0].respawn);
  EXPECT_DOUBLE_EQ(profile.processes[0].respawn_delay_s, 0.5);
  EXPECT_EQ(profile.processes[0].max_respawns, 2);
  EXPECT_TRUE(profile.processes[0].stop_on_failure);
  EXPECT_TRUE(profile.processes[1].required);
  EXPECT_FALSE(profile.processes[1].common_args);
  EXPECT_DOUBLE_EQ(profile.processes[0].hang_timeout_s, 2.5);
  EXPECT_DOUBLE_EQ(profile.processes[1].respawn_delay_s, 1.0);  // the default
  EXPECT_EQ(profile.processes[0].respawn_args, (std::vector<std::string>{"--resume", "3"}));
  EXPECT_DOUBLE_EQ(profile.processes[1].hang_timeout_s, 0.0);  // the watchdog is off unless asked for
}

TEST(LaunchProfile, HangTimeoutMustBeSeconds) {
  const auto file = write_profile("launch_hang.yaml", R"(
variables: {hang: "soon", delay: "0.2"}
processes:
  - name: a
    command: source
    hang_timeout: "${hang}"
    respawn_delay: "${delay}"
)");
  EXPECT_NE(error_of([&] { resolve(load_profile(file), {}); }).find("process 'a': hang_timeout is 'soon'"), std::string::npos);
  EXPECT_DOUBLE_EQ(resolve(load_profile(file), {{"hang", "4"}}).processes[0].respawn_delay_s, 0.2);
  EXPECT_NE(error_of([&] { resolve(load_profile(file), {{"hang", "4"}, {"delay", "x"}}); }).find("respawn_delay is 'x'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { resolve(load_profile(file), {{"hang", "-1"}}); }).find("hang_timeout"), std::string::npos);
}

// Processes switched on by a variable, and writers that wait for exactly the readers that run.
TEST(LaunchProfile, EnabledProcessesAndReaderCounts) {
  const auto file = write_profile("launch_readers.yaml", R"(
variables: {view: "false"}
processes:
  - name: view
    command: view
    enabled: "${view}"
    reads: [t/frames, t/tracks]
  - name: sink
    command: sink
    reads: [t/tracks]
  - name: source
    command: source
    args: [--wait-subscribers, "${readers:t/frames}", --tracks-readers, "${readers:t/tracks}"]
)");
  const auto profile = load_profile(file);
  const auto plain = resolve(profile, {});
  ASSERT_EQ(plain.processes.size(), 2u);
  EXPECT_EQ(plain.processes[0].name, "sink");
  EXPECT_EQ(plain.processes[1].args, (std::vector<std::string>{"--wait-subscribers", "0", "--tracks-readers", "1"}));
  const auto viewed = resolve(profile, {{"view", "true"}});
  ASSERT_EQ(viewed.processes.size(), 3u);
  EXPECT_EQ(viewed.processes[2].args, (std::vector<std::string>{"--wait-subscribers", "1", "--tracks-readers", "2"}));

  EXPECT_NE(error_of([&] { resolve(profile, {{"view", "maybe"}}); }).find("process 'view': enabled is 'maybe'"), std::string::npos);
  const auto typo = write_profile("launch_readers_typo.yaml",
                                  "processes:\n  - name: a\n    command: a\n    args: [\"${readers:t/framez}\"]\n");
  EXPECT_NE(error_of([&] { resolve(load_profile(typo), {}); }).find("no process of the profile reads 't/framez'"),
            std::string::npos);
}

TEST(LaunchProfile, DefaultsMayNameOtherVariables) {
  const auto file = write_profile("launch_nested.yaml",
                                  "variables:\n  qos_dir: \"${profile_dir}/qos\"\nprocesses:\n"
                                  "  - name: a\n    command: a\n    env: {Q: \"${qos_dir}/a.xml\"}\n");
  const auto p = load_profile(file);
  EXPECT_EQ(resolve(p, {{"profile_dir", "/b"}}).processes.at(0).env.at("Q"), "/b/qos/a.xml");
  // A value given on the command line is taken as it is.
  EXPECT_EQ(resolve(p, {{"profile_dir", "/b"}, {"qos_dir", "/sec"}}).processes.at(0).env.at("Q"), "/sec/a.xml");
  // The launcher takes its own identity from the resolved qos_dir (launch_main.cpp).
  EXPECT_EQ(resolve(p, {{"profile_dir", "/b"}}).variables.at("qos_dir"), "/b/qos");
}

TEST(LaunchProfile, TypoIsNamedWithItsLine) {
  const auto file = write_profile("uavmot_profile_typo.yaml", "processes:\n  - name: a\n    command: source\n    respwn: true\n");
  const std::string error = error_of([&] { load_profile(file); });
  EXPECT_NE(error.find("uavmot_profile_typo.yaml:4"), std::string::npos) << error;
  EXPECT_NE(error.find("did you mean 'respawn'"), std::string::npos) << error;
}

TEST(LaunchProfile, BadValuesAndUndefinedVariables) {
  EXPECT_NE(error_of([&] { load_profile(write_profile("uavmot_p1.yaml", "processes:\n  - name: a\n    command: x\n    max_respawns: many\n")); })
                .find("expected an integer"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_profile(write_profile("uavmot_p2.yaml", "processes: []\n")); }).find("needs a list"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_profile(write_profile("uavmot_p3.yaml", "processes:\n  - name: a\n    command: x\n  - name: a\n    command: y\n")); })
                .find("duplicate"),
            std::string::npos);
  const auto p = load_profile(write_profile("uavmot_p4.yaml", "processes:\n  - name: a\n    command: x\n    args: [\"${nope}\"]\n"));
  EXPECT_NE(error_of([&] { resolve(p, {}); }).find("'${nope}' is not defined"), std::string::npos);
  EXPECT_THROW(load_profile("/nonexistent/profile.yaml"), InputError);
}

}  // namespace
}  // namespace uavmot::launch
