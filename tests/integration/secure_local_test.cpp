// DDS Security on one host (issue 20): bringup/local.yaml with --set qos_dir=DIR from
// tools/make_security.sh, the same switch as the split deployment.
// - The lossless chain with security on writes byte-identical results to the one without, and a
//   participant without a certificate sees none of its health (it cannot join the domain), while
//   `uavmot status` with its own certificate sees the whole chain.
// - Health is per node: with the sink's certificate a participant cannot report as motion, neither
//   in motion's partition (its writer is refused) nor in its own (status does not take it as
//   motion's); the real motion certificate can.

#include <set>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "launched_chain.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;

std::string make_security(const std::string& root) {
  const std::string dir = root + "/security";
  ChildProcess make({"/bin/sh", build_paths::source_dir() + "/tools/make_security.sh", dir}, root + "/make_security.log");
  EXPECT_EQ(make.wait(std::chrono::seconds(60)), 0) << make.log();
  return dir;
}

// `uavmot status --once --json` on `domain`: its exit code and the (component, stream) of every row.
struct StatusSeen {
  std::optional<int> code;
  std::set<std::pair<std::string, std::string>> rows;
  std::string log;
};
std::unique_ptr<ChildProcess> start_status(const std::string& log, int domain, const std::string& profiles, double wait_s) {
  std::map<std::string, std::string> env;
  if (!profiles.empty()) env["UAVMOT_QOS_PROFILES"] = profiles;
  return std::make_unique<ChildProcess>(std::vector<std::string>{binary("uavmot"), "status", "--once", "--json", "--wait",
                                                                 std::to_string(wait_s), "--domain", std::to_string(domain)},
                                        log, env);
}
StatusSeen finish_status(ChildProcess& status) {
  StatusSeen seen;
  seen.code = status.wait(std::chrono::seconds(60));
  seen.log = status.log();
  // stdout (the JSON line) and stderr (log lines) share the log file.
  std::istringstream lines(seen.log);
  for (std::string line; std::getline(lines, line);) {
    if (!nlohmann::json::accept(line)) continue;
    const auto table = nlohmann::json::parse(line);
    if (!table.is_array()) continue;
    for (const auto& row : table) seen.rows.insert({row["component"].get<std::string>(), row["stream_id"].get<std::string>()});
  }
  return seen;
}

TEST(SecureLocalChain, SameResultsAsWithoutSecurityAndOutsidersCannotJoin) {
  const std::string root = testing::fresh_dir("secure_local");
  const std::string sequence = root + "/paper";
  ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", "3", "--frames", "200", "--out", sequence},
                   root + "/sim.log");
  ASSERT_EQ(sim.wait(std::chrono::seconds(180)), 0) << sim.log();
  const std::string security = make_security(root);

  ChildProcess plain({binary("uavmot"), "launch", testing::kLocalProfile, "--input", sequence, "--out", root + "/plain", "--set",
                      "domain=191"},
                     root + "/plain.log");
  ASSERT_EQ(plain.wait(std::chrono::seconds(300)), 0) << plain.log();

  // Fast DDS 2.9 gives up a PKI-DH handshake after a fixed number of resends (airground_test.cpp):
  // a start where two nodes never authenticated each other is tried again, at most twice.
  std::optional<int> code;
  std::string out, log;
  std::set<std::string> outsider_saw, insider_saw;
  int polls = 0;
  for (int attempt = 0; attempt < 3 && code != 0; ++attempt) {
    out = root + "/secure_" + std::to_string(attempt);
    const int domain = 192 + attempt;
    if (attempt > 0) std::printf("[secure_local] the secure run failed (exit %d); starting it again (%d of 2)\n", code.value_or(-1), attempt);
    ChildProcess launch({binary("uavmot"), "launch", testing::kLocalProfile, "--input", sequence, "--out", out, "--set",
                         "domain=" + std::to_string(domain), "--set", "qos_dir=" + security},
                        out + ".log");
    // Once results flow, status with no certificate and with its own, side by side.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (testing::last_frame_written(out + "/tracks_obb.csv") < 5 && std::chrono::steady_clock::now() < deadline &&
           !launch.wait(std::chrono::milliseconds(0)).has_value()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    // Polled while the chain runs (each poll a new participant: one whose handshake with a node
    // timed out still sees the others, and the next poll sees that node).
    outsider_saw.clear();
    insider_saw.clear();
    while (!launch.wait(std::chrono::milliseconds(0)).has_value()) {
      const std::string n = std::to_string(++polls);
      auto status_plain = start_status(out + "_status_plain_" + n + ".log", domain, "", 3);
      auto status_secure = start_status(out + "_status_secure_" + n + ".log", domain, security + "/status.xml", 3);
      const StatusSeen outsider = finish_status(*status_plain);
      const StatusSeen insider = finish_status(*status_secure);
      EXPECT_EQ(outsider.code, 1) << "status without a certificate found the secure chain:\n" << outsider.log;
      for (const auto& row : outsider.rows) outsider_saw.insert(row.first);
      if (insider.code == 0) {
        for (const auto& row : insider.rows) insider_saw.insert(row.first);
      }
    }
    code = launch.wait(std::chrono::seconds(300));
    log = launch.log();
  }
  ASSERT_EQ(code, 0) << log;
  EXPECT_NE(log.find("watchdog: watching uavmot/health of motion"), std::string::npos) << log;
  // The watchdog, with the launcher's own certificate, reads the nodes' reports.
  EXPECT_NE(log.find("watchdog: first health report of"), std::string::npos) << log;
  for (const char* file : {"tracks.txt", "tracks_obb.csv", "regions.txt", "homographies.txt"}) {
    const std::string secure_text = testing::read_file(out + "/" + file);
    EXPECT_FALSE(secure_text.empty()) << file;
    EXPECT_EQ(secure_text, testing::read_file(root + "/plain/" + file)) << file << " differs with security on";
  }
  // The outsider (no certificate) found nobody: status exits 1 with an empty table.
  EXPECT_TRUE(outsider_saw.empty()) << "polls: " << polls;
  // Status with its own certificate sees the chain's components.
  for (const char* c : {"source", "motion", "segmentation", "tracking", "sink"}) {
    EXPECT_TRUE(insider_saw.count(c)) << c << " missing from the secure status in " << polls << " polls";
  }
}

TEST(SecureHealth, AnotherNodesCertificateCannotReportAsMotion) {
  const std::string root = testing::fresh_dir("secure_health");
  const std::string security = make_security(root);
  const int domain = 196;
  auto forge = [&](const std::string& name, const std::string& identity, const std::string& component, const std::string& partition,
                   const std::string& stream) {
    std::vector<std::string> argv = {build_paths::binary_dir() + "/tests/uavmot-test-forge-health", "--component", component,
                                     "--stream", stream, "--seconds", "60", "--domain", std::to_string(domain)};
    if (!partition.empty()) argv.insert(argv.end(), {"--partition", partition});
    std::map<std::string, std::string> env;
    if (!identity.empty()) env["UAVMOT_QOS_PROFILES"] = security + "/" + identity + ".xml";
    return std::make_unique<ChildProcess>(argv, root + "/" + name + ".log", env);
  };
  // The sink's certificate in motion's partition: its own access control refuses the writer.
  auto in_motions_partition = forge("sink_in_motion_partition", "sink", "motion", "", "forged");
  EXPECT_EQ(in_motions_partition->wait(std::chrono::seconds(30)), 3) << in_motions_partition->log();
  EXPECT_NE(in_motions_partition->log().find("partition not found in rule"), std::string::npos) << in_motions_partition->log();
  // Running side by side: the sink's certificate reporting as motion in its own partition (the
  // forgery), and as itself (allowed); no certificate at all; the real motion certificate.
  auto as_motion = forge("sink_as_motion", "sink", "motion", "sink", "forged");
  auto as_itself = forge("sink_as_itself", "sink", "sink", "", "forged");
  auto uncertified = forge("uncertified", "", "tracking", "", "forged");
  auto real_motion = forge("real_motion", "motion", "motion", "", "real");
  std::this_thread::sleep_for(std::chrono::seconds(1));
  // Polled until both allowed reports were seen: a PKI-DH handshake between the status participant
  // and one node can time out under load (see the chain test above), and each poll is a new
  // participant. The refused reports must be absent from every poll.
  std::set<std::pair<std::string, std::string>> seen_rows;
  std::string last_log;
  int polls = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(45);
  while (std::chrono::steady_clock::now() < deadline &&
         !(seen_rows.count({"motion", "real"}) && seen_rows.count({"sink", "forged"}))) {
    auto status = start_status(root + "/status_" + std::to_string(++polls) + ".log", domain, security + "/status.xml", 5);
    const StatusSeen seen = finish_status(*status);
    EXPECT_TRUE(seen.code == 0 || seen.code == 1) << seen.log;  // 1: this poll saw nobody
    EXPECT_FALSE(seen.rows.count({"motion", "forged"})) << "status took the sink's report as motion's:\n" << seen.log;
    EXPECT_FALSE(seen.rows.count({"tracking", "forged"})) << "an uncertified participant reported:\n" << seen.log;
    seen_rows.insert(seen.rows.begin(), seen.rows.end());
    last_log = seen.log;
  }
  EXPECT_TRUE(seen_rows.count({"motion", "real"})) << "the real motion's report is missing after " << polls << " polls:\n" << last_log;
  EXPECT_TRUE(seen_rows.count({"sink", "forged"})) << "the sink's own report is missing after " << polls << " polls:\n" << last_log;
  for (auto* p : {as_motion.get(), as_itself.get(), uncertified.get(), real_motion.get()}) {
    p->signal(SIGTERM);
    EXPECT_EQ(p->wait(std::chrono::seconds(20)), 0) << p->log();
  }
}

}  // namespace
}  // namespace uavmot
