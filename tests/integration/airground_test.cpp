// Air and ground as separate hosts: network namespaces joined by veth pairs, the air half of the
// chain (bringup/air.yaml) in one or two "UAV" namespaces, the ground half (bringup/ground.yaml)
// in another, real processes over real UDP. Needs root and `ip netns`; skipped otherwise.
//
// The downlink carries one compact but exact sample per frame (idl/downlink.idl), so the ground's files
// are byte-identical to `uavmot process`'s.

#include <arpa/inet.h>
#include <fcntl.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <net/if.h>
#include <sched.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "uavmot/build_paths/build_paths.hpp"

namespace uavmot {
namespace {
using testing::binary;
using testing::ChildProcess;
using testing::read_file;
namespace fs = std::filesystem;

const std::string kAirProfile = build_paths::source_dir() + "/bringup/air.yaml";
const std::string kGroundProfile = build_paths::source_dir() + "/bringup/ground.yaml";
constexpr const char* kIp = "/usr/bin/ip";
constexpr int kFrames = 80;         // first UAV's sequence
constexpr int kSecondFrames = 60;   // second UAV's sequence (another seed)
// The downlink budget: 1 Mbit/s at 25 fps.
constexpr double kBudgetBytesPerFrame = 1e6 / 8.0 / 25.0;

// Runs a shell command; returns its exit code.
int sh(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Runs a shell command and returns what it printed.
std::string capture(const std::string& command) {
  std::string out;
  if (FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r")) {
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) out.append(buffer, n);
    ::pclose(pipe);
  }
  return out;
}

int64_t lines(const std::string& file) {
  const std::string text = testing::read_file(file);
  return std::count(text.begin(), text.end(), '\n');
}

int last_frame_in(const std::string& mot_file) {
  std::ifstream in(mot_file);
  int last = 0;
  for (std::string line; std::getline(in, line);) last = std::max(last, std::stoi(line.substr(0, line.find(','))));
  return last;
}

// Payload bytes per downlink topic, from uavmot-downlink's last log lines ("TOPIC: N samples, B bytes").
std::map<std::string, uint64_t> downlink_bytes(const std::string& air_log) {
  std::map<std::string, uint64_t> out;
  const std::regex line(R"((uavmot/downlink/\w+): (\d+) samples, (\d+) bytes)");
  for (std::sregex_iterator it(air_log.begin(), air_log.end(), line), end; it != end; ++it) out[(*it)[1]] = std::stoull((*it)[3]);
  return out;
}

// A ground namespace and one or two air namespaces. One air: a veth pair air (10.200.0.1) <->
// ground (10.200.0.2). Two airs: each air's veth ends on a bridge in the ground namespace, the
// second air is 10.200.0.3. Names carry the test's pid so parallel runs never collide;
// everything is removed in the destructor.
class Link {
 public:
  explicit Link(int airs = 1) : ground_("uavmot-ground-" + std::to_string(::getpid())) {
    const std::string tag = std::to_string(::getpid() % 100000);
    for (int i = 0; i < airs; ++i) {
      air_.push_back("uavmot-air" + std::to_string(i) + "-" + std::to_string(::getpid()));
      air_dev_.push_back("va" + std::to_string(i) + "x" + tag);
      ground_dev_.push_back("vg" + std::to_string(i) + "x" + tag);
    }
    remove();
    const std::string ip = kIp;
    ok_ = sh(ip + " netns add " + ground_) == 0 && sh(ip + " -n " + ground_ + " link set lo up") == 0;
    if (airs > 1) {
      ok_ = ok_ && sh(ip + " -n " + ground_ + " link add br0 type bridge") == 0 &&
            sh(ip + " -n " + ground_ + " addr add 10.200.0.2/24 dev br0") == 0 &&
            sh(ip + " -n " + ground_ + " link set br0 up") == 0;
    }
    for (int i = 0; i < airs && ok_; ++i) {
      const std::string air_ip = i == 0 ? "10.200.0.1/24" : "10.200.0." + std::to_string(2 + i) + "/24";
      ok_ = sh(ip + " netns add " + air_[i]) == 0 &&
            sh(ip + " link add " + air_dev_[i] + " type veth peer name " + ground_dev_[i]) == 0 &&
            sh(ip + " link set " + air_dev_[i] + " netns " + air_[i]) == 0 &&
            sh(ip + " link set " + ground_dev_[i] + " netns " + ground_) == 0 &&
            sh(ip + " -n " + air_[i] + " addr add " + air_ip + " dev " + air_dev_[i]) == 0 &&
            sh(ip + " -n " + air_[i] + " link set " + air_dev_[i] + " up") == 0 &&
            sh(ip + " -n " + air_[i] + " link set lo up") == 0 &&
            (airs == 1 ? sh(ip + " -n " + ground_ + " addr add 10.200.0.2/24 dev " + ground_dev_[i])
                       : sh(ip + " -n " + ground_ + " link set " + ground_dev_[i] + " master br0")) == 0 &&
            sh(ip + " -n " + ground_ + " link set " + ground_dev_[i] + " up") == 0;
    }
  }
  ~Link() { remove(); }
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  bool ok() const { return ok_; }
  const std::string& air(int i = 0) const { return air_[static_cast<size_t>(i)]; }
  const std::string& ground() const { return ground_; }
  const std::string& air_dev(int i = 0) const { return air_dev_[static_cast<size_t>(i)]; }
  const std::string& ground_dev(int i = 0) const { return ground_dev_[static_cast<size_t>(i)]; }

  // argv prefix that runs a command inside a namespace.
  std::vector<std::string> in(const std::string& ns) const { return {kIp, "netns", "exec", ns}; }

  // Bytes an air host sent into the link (the downlink).
  uint64_t air_tx_bytes(int i = 0) const { return counter(air(i), air_dev(i), "tx_bytes"); }

  // Drops `percent` % of the packets leaving each side into the link (both directions).
  bool add_random_loss(int percent) const {
    for (const auto& [ns, dev] : {std::pair{air(), air_dev()}, std::pair{ground_, ground_dev()}}) {
      const std::string nft = std::string(kIp) + " netns exec " + ns + " nft ";
      if (sh(nft + "add table inet uavmot_loss") != 0 ||
          sh(nft + "'add chain inet uavmot_loss out { type filter hook output priority 0; }'") != 0 ||
          sh(nft + "add rule inet uavmot_loss out oifname " + dev + " numgen random mod 100 '<' " + std::to_string(percent) +
             " counter drop") != 0) {
        return false;
      }
    }
    return true;
  }
  // Packets the loss rules dropped on both sides.
  uint64_t dropped_packets() const {
    uint64_t total = 0;
    const std::regex packets(R"(counter packets (\d+))");
    for (const auto& ns : {air(), ground_}) {
      const std::string out = capture(std::string(kIp) + " netns exec " + ns + " nft list table inet uavmot_loss");
      std::smatch m;
      if (std::regex_search(out, m, packets)) total += std::stoull(m[1]);
    }
    return total;
  }

  // Drops every multicast packet in and out of both hosts: discovery must do without it.
  bool block_multicast() const {
    for (const auto& ns : {air(), ground_}) {
      const std::string nft = std::string(kIp) + " netns exec " + ns + " nft ";
      if (sh(nft + "add table inet uavmot_mcast") != 0 ||
          sh(nft + "'add chain inet uavmot_mcast out { type filter hook output priority 0; }'") != 0 ||
          sh(nft + "'add chain inet uavmot_mcast in { type filter hook input priority 0; }'") != 0 ||
          sh(nft + "add rule inet uavmot_mcast out ip daddr 224.0.0.0/4 drop") != 0 ||
          sh(nft + "add rule inet uavmot_mcast in ip daddr 224.0.0.0/4 drop") != 0) {
        return false;
      }
    }
    return true;
  }

  // Token bucket on the air's side of the link: the downlink carries at most `rate`.
  bool limit_downlink(const std::string& rate) const {
    return sh(std::string(kIp) + " netns exec " + air() + " tc qdisc add dev " + air_dev() + " root tbf rate " + rate +
              " burst 32kbit latency 400ms") == 0;
  }

  // The air's end of the link goes down (no carrier on either end) or comes back.
  bool set_link(bool up) const {
    return sh(std::string(kIp) + " -n " + air() + " link set " + air_dev() + (up ? " up" : " down")) == 0;
  }

 private:
  static uint64_t counter(const std::string& ns, const std::string& dev, const std::string& name) {
    const std::string text = capture(std::string(kIp) + " netns exec " + ns + " cat /sys/class/net/" + dev + "/statistics/" + name);
    return text.empty() ? 0 : std::stoull(text);
  }
  void remove() const {
    std::vector<std::string> all = air_;
    all.push_back(ground_);
    // Whatever still runs in our namespaces was started by this test: end it by pid first.
    for (const auto& ns : all) {
      std::istringstream pids(capture(std::string(kIp) + " netns pids " + ns));
      for (pid_t pid; pids >> pid;) ::kill(pid, SIGKILL);
    }
    for (const auto& ns : all) sh(std::string(kIp) + " netns del " + ns);  // takes its veth ends (and peers) along
  }

  std::string ground_;
  std::vector<std::string> air_, air_dev_, ground_dev_;
  bool ok_ = false;
};

// Every packet the air (10.200.0.1) sends over the link, read with a raw packet socket from a
// thread that entered the namespace (network namespaces are per thread). No tcpdump needed.
class LinkCapture {
 public:
  LinkCapture(const std::string& ns, const std::string& dev) {
    thread_ = std::thread([this, ns, dev] {
      const int ns_fd = ::open(("/var/run/netns/" + ns).c_str(), O_RDONLY);
      if (ns_fd < 0 || ::setns(ns_fd, CLONE_NEWNET) != 0) return;
      ::close(ns_fd);
      const int fd = ::socket(AF_PACKET, SOCK_RAW, htons(ETH_P_ALL));
      if (fd < 0) return;
      sockaddr_ll address{};
      address.sll_family = AF_PACKET;
      address.sll_protocol = htons(ETH_P_ALL);
      address.sll_ifindex = static_cast<int>(::if_nametoindex(dev.c_str()));
      timeval timeout{0, 100000};
      ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
      if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) { ::close(fd); return; }
      started_ = true;
      std::vector<char> packet(65536);
      while (!stop_) {
        const ssize_t n = ::recv(fd, packet.data(), packet.size(), 0);
        // Only what the air sends (IPv4 source 10.200.0.1): the downlink.
        if (n > 30 && static_cast<unsigned char>(packet[12]) == 0x08 && packet[13] == 0x00 &&
            static_cast<unsigned char>(packet[26]) == 10 && static_cast<unsigned char>(packet[27]) == 200 &&
            packet[28] == 0 && packet[29] == 1) {
          bytes_.append(packet.data(), static_cast<size_t>(n));
        }
      }
      ::close(fd);
    });
    for (int i = 0; i < 100 && !started_; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ~LinkCapture() { stop(); }
  bool started() const { return started_; }
  // Stops capturing; returns everything captured.
  const std::string& stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    return bytes_;
  }

 private:
  std::thread thread_;
  std::atomic<bool> started_{false}, stop_{false};
  std::string bytes_;
};

// One UAV of a run.
struct Air {
  std::string stream_id = "uav1";
  std::string sequence;  // empty: the first sequence
  int air_domain = 0;    // 0: link domain + 1
};

class AirGround : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (::geteuid() != 0 || sh(std::string(kIp) + " netns list") != 0) return;
    root_ = testing::fresh_dir("airground");
    for (const auto& [name, seed, frames] : {std::tuple{"paper", 11, kFrames}, std::tuple{"paper_b", 12, kSecondFrames}}) {
      const std::string sequence = root_ + "/" + name;
      ChildProcess sim({binary("uavmot-sim"), "--preset", "paper", "--seed", std::to_string(seed), "--frames",
                        std::to_string(frames), "--out", sequence},
                       root_ + "/sim_" + name + ".log");
      ASSERT_EQ(sim.wait(std::chrono::seconds(120)), 0) << sim.log();
      ChildProcess process({binary("uavmot-process"), sequence, "--out", root_ + "/process_" + name, "--quiet"},
                           root_ + "/process_" + name + ".log");
      ASSERT_EQ(process.wait(std::chrono::seconds(240)), 0) << process.log();
    }
    sequence_ = root_ + "/paper";
  }

  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root for network namespaces";
    if (sh(std::string(kIp) + " netns list") != 0) GTEST_SKIP() << "`ip netns` is not available";
    ASSERT_FALSE(sequence_.empty());
    link_ = std::make_unique<Link>();
    ASSERT_TRUE(link_->ok()) << "could not create the air/ground namespaces";
  }
  void TearDown() override { link_.reset(); }

  struct Run {
    std::optional<int> ground_code;
    std::vector<std::optional<int>> air_codes;
    std::string ground_log, out;
    std::vector<std::string> air_logs;
    uint64_t air_tx_bytes = 0;  // the first air
    std::string link_bytes;     // every packet the first air sent over the link
    bool captured = false;
    std::optional<int> air_code() const { return air_codes.at(0); }
    const std::string& air_log() const { return air_logs.at(0); }
  };

  // The ground half first (it waits for its inputs), then each air half; all must end by themselves.
  Run run_split(const std::string& name, int domain, const std::vector<std::string>& extra_sets = {},
                std::chrono::seconds timeout = std::chrono::seconds(170),
                const std::function<void(const ChildProcess& air)>& while_running = {}, std::vector<Air> airs = {Air{}}) {
    Run run;
    run.out = root_ + "/" + name;
    const uint64_t tx_before = link_->air_tx_bytes();
    auto args = [&](const std::string& profile, const std::string& sequence, const std::string& out) {
      std::vector<std::string> a = {binary("uavmot"), "launch", profile, "--input", sequence, "--out", out,
                                    "--set", "domain=" + std::to_string(domain)};
      for (const auto& s : extra_sets) a.insert(a.end(), {"--set", s});
      return a;
    };
    auto with_ns = [&](const std::string& ns, std::vector<std::string> argv) {
      auto full = link_->in(ns);
      full.insert(full.end(), argv.begin(), argv.end());
      return full;
    };
    auto ground_args = args(kGroundProfile, sequence_, run.out);
    std::string stream_ids;
    for (const Air& a : airs) stream_ids += (stream_ids.empty() ? "" : ",") + a.stream_id;
    ground_args.insert(ground_args.end(), {"--set", "streams=" + std::to_string(airs.size()), "--set", "stream_ids=" + stream_ids});
    ChildProcess ground(with_ns(link_->ground(), ground_args), root_ + "/" + name + "_ground.log");
    std::vector<std::unique_ptr<ChildProcess>> air;
    for (size_t i = 0; i < airs.size(); ++i) {
      const Air& a = airs[i];
      auto air_args = args(kAirProfile, a.sequence.empty() ? sequence_ : a.sequence, root_ + "/" + name + "_air" + std::to_string(i));
      air_args.insert(air_args.end(), {"--set", "stream_id=" + a.stream_id, "--set",
                                       "air_domain=" + std::to_string(a.air_domain ? a.air_domain : domain + 1)});
      air.push_back(std::make_unique<ChildProcess>(with_ns(link_->air(static_cast<int>(i)), air_args),
                                                   root_ + "/" + name + "_air" + std::to_string(i) + ".log"));
    }
    LinkCapture capture(link_->ground(), link_->ground_dev());
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    auto left = [&] {
      return std::max(std::chrono::milliseconds(1000),
                      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()));
    };
    if (while_running) while_running(*air[0]);
    run.ground_code = ground.wait(left());
    for (auto& a : air) run.air_codes.push_back(a->wait(left()));
    // A half that did not end by itself is stopped the way an operator would (the launcher stops its children).
    std::vector<ChildProcess*> all = {&ground};
    for (auto& a : air) all.push_back(a.get());
    for (ChildProcess* p : all) {
      if (!p->wait(std::chrono::milliseconds(0)).has_value()) {
        p->signal(SIGTERM);
        p->wait(std::chrono::seconds(20));
      }
    }
    run.link_bytes = capture.stop();
    run.captured = capture.started();
    for (auto& a : air) run.air_logs.push_back(a->log());
    run.ground_log = ground.log();
    run.air_tx_bytes = link_->air_tx_bytes() - tx_before;
    return run;
  }

  // The ground's results against `uavmot process` on the same sequence: the same bytes.
  static void expect_same_results(const std::string& out, const std::string& process_dir = root_ + "/process_paper") {
    ASSERT_FALSE(read_file(process_dir + "/tracks.txt").empty()) << "the in-process run found no tracks: nothing would be compared";
    for (const char* file : {"homographies.txt", "tracks.txt", "tracks_obb.csv", "regions.txt"}) {
      EXPECT_EQ(read_file(out + "/" + file), read_file(process_dir + "/" + file)) << out << "/" << file;
    }
  }

  static std::string root_, sequence_;
  std::unique_ptr<Link> link_;
};
std::string AirGround::root_, AirGround::sequence_;

TEST_F(AirGround, LosslessSplitDeliversTheInProcessResultsAndOnlyCompactTopicsCrossTheLink) {
  const Run run = run_split("lossless", 120);
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air ---\n" << run.air_log();
  ASSERT_EQ(run.air_code(), 0) << run.air_log();
  expect_same_results(run.out);
  // What the downlink does not carry is not pretended: no features.csv, no clusters.txt.
  EXPECT_FALSE(fs::exists(run.out + "/features.csv"));
  EXPECT_FALSE(fs::exists(run.out + "/clusters.txt"));

  // Payload per frame (the downlink's own count) and everything on the wire per frame, discovery
  // and health included. One 8-bit frame of the sequence alone is larger than all of it.
  const auto payload = downlink_bytes(run.air_log());
  ASSERT_EQ(payload.count("uavmot/downlink/results"), 1u) << run.air_log();
  const uint64_t payload_total = payload.at("uavmot/downlink/results");
  std::printf("[airground] lossless: %.1f regions and %.1f tracks per frame\n", static_cast<double>(lines(run.out + "/regions.txt")) / kFrames,
              static_cast<double>(lines(run.out + "/tracks_obb.csv") - 1) / kFrames);
  const double wire_per_frame = static_cast<double>(run.air_tx_bytes) / kFrames;
  std::printf("[airground] lossless: payload %.0f bytes per frame (%.3f Mbit/s at 25 fps); on the wire %.0f (%.3f Mbit/s)\n",
              static_cast<double>(payload_total) / kFrames, payload_total * 25.0 * 8.0 / kFrames / 1e6, wire_per_frame,
              wire_per_frame * 25.0 * 8.0 / 1e6);
  EXPECT_LT(static_cast<double>(payload_total) / kFrames, kBudgetBytesPerFrame) << "tracks + regions + motion over 1 Mbit/s";
  // A short run pays discovery and health once: allow 25 % over the budget on the wire.
  EXPECT_LT(wire_per_frame, 1.25 * kBudgetBytesPerFrame);
  const auto frame_bytes = fs::file_size(fs::directory_iterator(sequence_ + "/img1")->path());
  EXPECT_LT(wire_per_frame, frame_bytes / 4.0) << "frames (" << frame_bytes << " bytes each, compressed on disk) crossed the link";

  // Without security the stream id and the downlink's topic names are readable on the wire (the
  // control for the security test). The air's own chain (frames, motion, segmentation, tracks)
  // runs on shared memory in its own domain: not even its discovery reaches the link.
  ASSERT_TRUE(run.captured);
  EXPECT_NE(run.link_bytes.find("uav1"), std::string::npos);
  EXPECT_NE(run.link_bytes.find("uavmot/downlink/results"), std::string::npos);
  for (const char* internal : {"uavmot/frames", "uavmot/motion", "uavmot/segmentation", "uavmot/tracks"}) {
    EXPECT_EQ(run.link_bytes.find(internal), std::string::npos) << internal << " appeared on the link";
  }
}

TEST_F(AirGround, FivePercentRandomLossLosesNoReliableSample) {
  ASSERT_TRUE(link_->add_random_loss(5)) << "nft could not add the loss rule";
  const Run run = run_split("loss", 122);
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air ---\n" << run.air_log();
  ASSERT_EQ(run.air_code(), 0) << run.air_log();
  const uint64_t dropped = link_->dropped_packets();
  std::printf("[airground] loss: nft dropped %llu packets\n", static_cast<unsigned long long>(dropped));
  EXPECT_GE(dropped, 5u) << "the loss rule dropped (almost) nothing: the test would not show anything";
  expect_same_results(run.out);
}

// Fast DDS Discovery Server in the ground namespace instead of multicast, which the link drops.
TEST_F(AirGround, DiscoveryServerReplacesBlockedMulticastAndSurvivesARestart) {
  ASSERT_TRUE(link_->block_multicast()) << "nft could not block multicast";
  const std::string server_log = root_ + "/discovery_server.log";
  auto start_server = [&] {
    auto argv = link_->in(link_->ground());
    argv.insert(argv.end(), {"/usr/bin/fast-discovery-server", "-i", "0", "-l", "10.200.0.2", "-p", "11811"});
    return std::make_unique<ChildProcess>(argv, server_log);
  };
  // Without the server the halves never find each other: the ground is still waiting after 12 s.
  {
    const Run run = run_split("no_server", 124, {}, std::chrono::seconds(12));
    EXPECT_FALSE(run.ground_code.has_value()) << "the halves met with multicast blocked and no server:\n" << run.ground_log;
    EXPECT_FALSE(fs::exists(run.out + "/tracks.txt") && !read_file(run.out + "/tracks.txt").empty());
  }
  auto server = start_server();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  // The server dies mid-run and comes back; the matched endpoints carry on and the run completes.
  const Run run = run_split("discovery_server", 126, {"discovery_server=10.200.0.2:11811"}, std::chrono::seconds(170),
                            [&](const ChildProcess&) {
    // Once the chain runs (every endpoint matched, results flowing: ~10 frames' worth crossed the link).
    const uint64_t start = link_->air_tx_bytes();
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (link_->air_tx_bytes() - start < 40000 && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    server->signal(SIGTERM);
    ASSERT_TRUE(server->wait(std::chrono::seconds(10)).has_value());
    std::this_thread::sleep_for(std::chrono::seconds(1));
    server = start_server();
  });
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air ---\n" << run.air_log();
  ASSERT_EQ(run.air_code(), 0) << run.air_log();
  expect_same_results(run.out);
  EXPECT_NE(read_file(server_log).find("Server is running"), std::string::npos) << read_file(server_log);
}

// DDS Security on (tools/make_security.sh, --set qos_dir=DIR): the chain still delivers the same
// results, nothing readable crosses the link, and participants without a certificate, without
// permission, or with permissions the CA did not sign can neither read nor inject.
TEST_F(AirGround, SecurityEncryptsTheLinkAndKeepsOutsidersOutOfTheGroundStation) {
  const std::string security = root_ + "/security";
  ChildProcess make({"/bin/sh", build_paths::source_dir() + "/tools/make_security.sh", security}, root_ + "/make_security.log");
  ASSERT_EQ(make.wait(std::chrono::seconds(60)), 0) << make.log();
  // A rogue: the real sink's certificate, with permissions that let it publish everything (every
  // publish criterion, health's partitioned one included, made "*"), signed by a CA of its own.
  // Its own Fast DDS accepts them; the ground must not.
  const std::string rogue = root_ + "/security_rogue";
  ChildProcess make_rogue({"/bin/sh", "-c",
                           "set -e; sh " + build_paths::source_dir() + "/tools/make_security.sh " + rogue + " >/dev/null; cd " + rogue +
                               "; sed 's|<publish>.*</publish>|<publish><topics><topic>*</topic></topics></publish>|' "
                               "permissions.xml > all.xml; openssl smime -sign -in all.xml -text -out all.smime -signer ca.pem -inkey ca.key; "
                               "sed -e 's|" + rogue + "/sink.pem|" + security + "/sink.pem|' -e 's|" + rogue + "/sink.key|" + security +
                               "/sink.key|' -e 's|identity_ca</name><value>file://" + rogue + "/ca.pem|identity_ca</name><value>file://" +
                               security + "/ca.pem|' -e 's|permissions.smime|all.smime|' sink.xml > forged.xml"},
                          root_ + "/make_rogue.log");
  ASSERT_EQ(make_rogue.wait(std::chrono::seconds(60)), 0) << make_rogue.log();

  auto in_ground = [&](const std::string& name, const std::map<std::string, std::string>& env, std::vector<std::string> argv) {
    auto full = link_->in(link_->ground());
    full.push_back("/usr/bin/env");
    for (const auto& [k, v] : env) full.push_back(k + "=" + v);
    full.insert(full.end(), argv.begin(), argv.end());
    full.insert(full.end(), {"--domain", "128", "--transport", "udp"});
    return std::make_unique<ChildProcess>(full, root_ + "/" + name + ".log");
  };
  auto sink = [&](const std::string& name, const std::map<std::string, std::string>& env) {
    return in_ground(name, env, {binary("uavmot-sink"), "--downlink", "--out", root_ + "/" + name});
  };
  auto injector = [&](const std::string& name, const std::map<std::string, std::string>& env) {
    return in_ground(name, env, {build_paths::binary_dir() + "/tests/uavmot-test-inject", "--seconds", "40",
                                 "--frames", std::to_string(kFrames), "--mode", "live"});
  };
  // Readers: no certificate at all (the plain profiles), and the source's identity, which may read only health.
  auto plain = sink("outsider_plain", {});
  auto unauthorised = sink("outsider_source_identity", {{"UAVMOT_QOS_PROFILES", security + "/source.xml"}});
  // Writers of made-up tracks for uav1: no certificate; the sink's identity, which may not publish
  // tracks; the forged permissions.
  auto inject_plain = injector("inject_plain", {});
  auto inject_sink = injector("inject_sink_identity", {{"UAVMOT_QOS_PROFILES", security + "/sink.xml"}});
  auto inject_forged = injector("inject_forged_permissions", {{"UAVMOT_QOS_PROFILES", rogue + "/forged.xml"}});
  // Fast DDS 2.9 with security now and then leaves two of the air's own nodes unmatched for good
  // (session 5: about one start in four; its library has none of the later PKI-DH handshake
  // settings). The launch now heals most such starts itself: the process whose readers never
  // matched exits and is respawned (docs/deployment.md, "Endpoints that never match"). A start it
  // could not heal (the air stops for want of readers) is retried, and said so, up to two times; a
  // third failure fails the test.
  auto air_never_matched = [](const Run& r) {
    return r.air_code() != 0 && (r.air_log().find("no subscriber within") != std::string::npos ||
                                 r.air_log().find("readers for") != std::string::npos);
  };
  Run run = run_split("secure", 128, {"qos_dir=" + security});
  for (int retry = 1; retry <= 2 && air_never_matched(run); ++retry) {
    std::printf("[airground] secure: the air's nodes did not all authenticate each other; starting the run again (%d of 2)\n",
                retry);
    run = run_split("secure_again_" + std::to_string(retry), 128, {"qos_dir=" + security});
  }
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air ---\n" << run.air_log();
  ASSERT_EQ(run.air_code(), 0) << run.air_log();
  expect_same_results(run.out);
  EXPECT_EQ(read_file(run.out + "/tracks_obb.csv").find(",424242,"), std::string::npos) << "an injected track reached the files";
  ASSERT_TRUE(run.captured);
  EXPECT_GT(run.link_bytes.size(), 50000u) << "the capture saw (almost) nothing";
  EXPECT_EQ(run.link_bytes.find("uav1"), std::string::npos) << "the stream id crossed the link in plain text";
  // (Topic names do cross in plain text, inside the signed permissions document that the
  // authentication handshake carries; the samples and the endpoint discovery are encrypted.)
  // The outsider without a certificate got no sample: still waiting (no end of stream). The one with
  // the source's identity was refused its readers by access control.
  EXPECT_FALSE(plain->wait(std::chrono::milliseconds(0)).has_value()) << plain->log();
  if (!unauthorised->wait(std::chrono::milliseconds(0)).has_value()) {
    ADD_FAILURE() << "a node without read permission is running a sink:\n" << unauthorised->log();
  }
  EXPECT_NE(unauthorised->log().find("topic not found in allow rule"), std::string::npos) << unauthorised->log();
  // The sink's identity may not publish tracks: its own access control refuses the writer.
  EXPECT_EQ(inject_sink->wait(std::chrono::seconds(10)), 3) << inject_sink->log();
  for (auto* p : {plain.get(), unauthorised.get(), inject_plain.get(), inject_forged.get()}) {
    p->signal(SIGTERM);
    p->wait(std::chrono::seconds(10));
  }
  // The other two wrote all along. The forged one matched no reader; the plain one only its
  // fellow outsider, the plain sink (two unauthenticated participants do talk to each other).
  for (auto* p : {inject_plain.get(), inject_forged.get()}) EXPECT_EQ(p->log().find("wrote 0 samples"), std::string::npos) << p->log();
  EXPECT_NE(inject_forged->log().find("matched at most 0 reader(s)"), std::string::npos) << inject_forged->log();
  EXPECT_NE(inject_forged->log().find("Error validating remote permissions"), std::string::npos) << inject_forged->log();
  EXPECT_NE(inject_plain->log().find("matched at most 1 reader(s)"), std::string::npos) << inject_plain->log();
  // Neither outsider sink got anything from the air: no homographies, no regions, no real track.
  for (const char* name : {"outsider_plain", "outsider_source_identity"}) {
    for (const char* file : {"homographies.txt", "regions.txt"}) {
      const std::string path = root_ + "/" + name + "/" + file;
      EXPECT_TRUE(!fs::exists(path) || read_file(path).empty()) << name << " read " << file;
    }
    std::ifstream tracks(root_ + "/" + name + "/tracks.txt");
    for (std::string line; std::getline(tracks, line);) EXPECT_NE(line.find(",424242,"), std::string::npos) << name << ": " << line;
  }
}

// Two UAVs with their own stream ids and sequences feed one ground station over a bridge; the
// ground files each stream apart, each equal to `uavmot process` of that UAV's sequence.
TEST_F(AirGround, TwoUavsFeedOneGroundStationEachStreamKeptApart) {
  link_.reset();
  link_ = std::make_unique<Link>(2);
  ASSERT_TRUE(link_->ok()) << "could not create two air namespaces and the bridge";
  const Run run = run_split("two_uavs", 130, {}, std::chrono::seconds(240), {},
                            {Air{"uav1", sequence_, 131}, Air{"uav2", root_ + "/paper_b", 132}});
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air 0 ---\n" << run.air_logs[0] << "\n--- air 1 ---\n" << run.air_logs[1];
  ASSERT_EQ(run.air_codes[0], 0) << run.air_logs[0];
  ASSERT_EQ(run.air_codes[1], 0) << run.air_logs[1];
  expect_same_results(run.out + "/uav1", root_ + "/process_paper");
  expect_same_results(run.out + "/uav2", root_ + "/process_paper_b");
  EXPECT_EQ(last_frame_in(run.out + "/uav2/homographies.txt"), kSecondFrames);
}

// The link goes down for longer than the 5 s lease (the halves drop each other) and comes back:
// they find each other again, the downlink's history fills the gap, and the ground's files are
// complete.
TEST_F(AirGround, LinkDownAndUpAgainRediscoversAndResumes) {
  const Run run = run_split("link_drop", 133, {}, std::chrono::seconds(200), [&](const ChildProcess&) {
    const uint64_t start = link_->air_tx_bytes();
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (link_->air_tx_bytes() - start < 60000 && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(link_->set_link(false));
    std::this_thread::sleep_for(std::chrono::seconds(8));
    ASSERT_TRUE(link_->set_link(true));
  });
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air ---\n" << run.air_log();
  ASSERT_EQ(run.air_code(), 0) << run.air_log();
  // The downlink lost its ground reader (lease expired) and found it again (rediscovered).
  const std::regex lost(R"(uavmot/downlink/\w+: waiting for 1 reader\(s\), 0 matched)");
  const std::regex found(R"(uavmot/downlink/\w+: 1 reader\(s\) matched, going on)");
  EXPECT_TRUE(std::regex_search(run.air_log(), lost)) << run.air_log();
  EXPECT_TRUE(std::regex_search(run.air_log(), found)) << run.air_log();
  expect_same_results(run.out);
}

// The link limited to 2 Mbit/s (tbf), live mode at 25 fps, and a JPEG preview asked for at far
// more than its share: 640 px frames at 10 Hz (about 5 Mbit/s) with a 1 Mbit/s share
// (flow controller). The preview gives way (most images never leave the air); the results do
// not (every sample the downlink wrote arrived, and the end of stream got through).
TEST_F(AirGround, OnATwoMegabitLinkThePreviewNotTheTracksGivesWay) {
  ASSERT_TRUE(link_->limit_downlink("2mbit")) << "tc could not add the tbf qdisc";
  const std::string previews = root_ + "/tbf_previews";
  const Run run = run_split("tbf", 135,
                            // 640 px JPEGs (about 60 kB): 10 Hz of them need twice the link, and a 1 Mbit/s share
                            // still passes several within the 3.2 s sequence (full-size 160 kB images passed
                            // one or two, and none in a run whose preview started late).
                            {"mode=live", "preview_rate=10", "preview_width=640", "preview_quality=90", "preview_kbps=1000",
                             "preview_dir=" + previews},
                            std::chrono::seconds(60));
  const std::string tc = capture(std::string(kIp) + " netns exec " + link_->air() + " tc -s qdisc show dev " + link_->air_dev());
  EXPECT_NE(tc.find("tbf"), std::string::npos) << tc;
  ASSERT_EQ(run.ground_code, 0) << run.ground_log << "\n--- air ---\n" << run.air_log();
  ASSERT_EQ(run.air_code(), 0) << run.air_log();
  // Samples written by the downlink (air log) and received by the sink (ground log), per topic.
  auto counts = [](const std::string& log, const std::string& suffix) {
    std::map<std::string, std::pair<uint64_t, uint64_t>> out;
    const std::regex line(R"((uavmot/downlink/\w+): (\d+) samples, (\d+) bytes)" + suffix);
    for (std::sregex_iterator it(log.begin(), log.end(), line), end; it != end; ++it) {
      out[(*it)[1]] = {std::stoull((*it)[2]), std::stoull((*it)[3])};
    }
    return out;
  };
  const auto sent = counts(run.air_log(), "");
  const auto received = counts(run.ground_log, " received");
  const std::string results = "uavmot/downlink/results";
  ASSERT_TRUE(sent.count(results) && received.count(results)) << run.air_log() << run.ground_log;
  EXPECT_EQ(received.at(results).first, sent.at(results).first) << "results lost on the link";
  EXPECT_GE(sent.at(results).first, 10u) << "the chain produced (almost) nothing: the comparison would be empty";
  const std::string preview = "uavmot/downlink/preview";
  ASSERT_TRUE(sent.count(preview) && received.count(preview)) << run.air_log() << run.ground_log;
  const auto [preview_sent, preview_sent_bytes] = sent.at(preview);
  const auto [preview_received, preview_received_bytes] = received.at(preview);
  const double seconds = kFrames / 25.0;
  // Preview images that were due at 10 Hz, and how many went (uavmot-downlink's log).
  std::smatch due;
  ASSERT_TRUE(std::regex_search(run.air_log(), due, std::regex(R"(preview: (\d+) of (\d+) images due)"))) << run.air_log();
  const uint64_t preview_due = std::stoull(due[2]);
  std::printf("[airground] tbf 2 Mbit/s, live, preview 10 Hz 640 px with a 1 Mbit/s share: %llu images due, %llu sent "
              "(%llu bytes), %llu received (%.2f Mbit/s over the %.1f s of the sequence); results: %llu of %llu samples "
              "received; air sent %llu bytes\n%s\n",
              static_cast<unsigned long long>(preview_due), static_cast<unsigned long long>(preview_sent),
              static_cast<unsigned long long>(preview_sent_bytes), static_cast<unsigned long long>(preview_received),
              preview_received_bytes * 8.0 / seconds / 1e6, seconds, static_cast<unsigned long long>(received.at(results).first),
              static_cast<unsigned long long>(sent.at(results).first), static_cast<unsigned long long>(run.air_tx_bytes), tc.c_str());
  // Full-size images at 10 Hz would need several times the link; the preview gave way (far fewer
  // images than due), got through, and stayed within its share.
  const double image_bytes = preview_sent > 0 ? static_cast<double>(preview_sent_bytes) / preview_sent : 0.0;
  EXPECT_GT(image_bytes * 8.0 * 10.0, 2e6) << "the preview did not ask for more than the link carries";
  EXPECT_GE(preview_received, 1u) << "no preview got through at all";
  EXPECT_LT(preview_sent * 2, preview_due) << "the preview did not give way";
  EXPECT_LT(preview_received_bytes * 8.0 / seconds, 1.3e6) << "the preview took more than its 1 Mbit/s";
  EXPECT_EQ(static_cast<uint64_t>(std::distance(fs::directory_iterator(previews), fs::directory_iterator())), preview_received);
  // The chain kept running to the end of the sequence. (How many frames the results cover depends
  // on the host: in live mode a loaded UAV skips frames; those that were sent all arrived, above.)
  const int last_tracks = last_frame_in(run.out + "/tracks.txt"), last_motion = last_frame_in(run.out + "/homographies.txt");
  std::printf("[airground] tbf: last frame with tracks %d, with motion %d; %lld frames with motion\n", last_tracks, last_motion,
              static_cast<long long>(lines(run.out + "/homographies.txt")));
  EXPECT_GE(last_motion, kFrames - 5) << "the results stopped before the end of the sequence";
  EXPECT_GE(last_tracks, kFrames - 5) << "the tracks stopped before the end of the sequence";
}

}  // namespace
}  // namespace uavmot
