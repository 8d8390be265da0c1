// Frame hop benchmark: how long a frame takes from one process to another over Fast DDS.
//
//   uavmot-bench-frame-hop [--frames N] [--json OUT]
//
// For 1080p mono8 (2 MB) and 4K bgr8 (24 MB) frames, over shared memory ("local") and UDP
// loopback ("udp"): paced live publishing at 30 and 60 Hz (latency median / p99, loss), and
// lossless publishing as fast as the subscriber takes (throughput, loss). The subscriber is this
// program re-executed with --role sub, a separate process. Latency is receive time minus the
// DDS source timestamp (one host, one clock). Also measured: a plain in-process copy of the frame.

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "framePubSubTypes.h"
#include "uavmot/core/app.hpp"
#include "uavmot/core/logging.hpp"
#include "uavmot/dds/participant.hpp"

namespace uavmot {
namespace {
using Clock = std::chrono::steady_clock;

int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size() - 1) + 0.5))];
}

struct Case {
  std::string name;
  int width, height, channels;
  std::string transport;  // local | udp
  std::string mode;       // live | lossless
  double rate_hz;         // 0 = as fast as possible (lossless)
};

dds::DdsOptions dds_options(const std::string& transport, const std::string& mode, int domain, const std::string& name) {
  dds::DdsOptions o;
  o.domain_id = domain;
  o.participant_profile = transport;
  o.mode = dds::parse_delivery_mode(mode);
  o.participant_name = name;
  return o;
}

// Subscriber process: prints one JSON line with latencies when the end-of-stream marker arrives.
int run_subscriber(const std::string& transport, const std::string& mode, int domain) {
  dds::Participant participant(dds_options(transport, mode, domain, "bench-sub"));
  auto reader = participant.make_reader<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
  std::vector<double> latencies_ms;
  int64_t bytes = 0;
  msg::Frame sample;
  eprosima::fastdds::dds::SampleInfo info;
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  bool done = false;
  while (!done && Clock::now() < deadline) {
    if (!reader->wait_for_data(std::chrono::milliseconds(200))) continue;
    while (reader->take(sample, &info)) {
      if (sample.end_of_stream()) {
        done = true;
        break;
      }
      const int64_t sent = static_cast<int64_t>(info.source_timestamp.seconds()) * 1'000'000'000LL + info.source_timestamp.nanosec();
      latencies_ms.push_back(static_cast<double>(wall_ns() - sent) / 1e6);
      bytes += static_cast<int64_t>(sample.data().size());
    }
  }
  nlohmann::json j;
  j["received"] = latencies_ms.size();
  j["bytes"] = bytes;
  j["latency_median_ms"] = percentile(latencies_ms, 0.5);
  j["latency_p99_ms"] = percentile(latencies_ms, 0.99);
  std::cout << j.dump() << std::endl;
  return 0;
}

nlohmann::json run_case(const Case& c, int frames, int domain, const std::string& self) {
  const std::string out_file = fmt::format("/tmp/uavmot_bench_sub_{}.json", ::getpid());
  const pid_t child = ::fork();
  if (child == 0) {
    std::freopen(out_file.c_str(), "w", stdout);
    ::execl(self.c_str(), self.c_str(), "--role", "sub", "--transport", c.transport.c_str(), "--mode", c.mode.c_str(),
            "--domain", std::to_string(domain).c_str(), nullptr);
    ::_exit(127);
  }
  dds::Participant participant(dds_options(c.transport, c.mode, domain, "bench-pub"));
  auto writer = participant.make_writer<msg::FramePubSubType>(dds::kFramesTopic, dds::TopicClass::Frames);
  nlohmann::json result;
  result["case"] = c.name;
  if (!writer->wait_for_matched(1, std::chrono::seconds(20))) {
    result["error"] = "subscriber never matched";
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    return result;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let discovery settle in both directions
  msg::Frame sample;
  sample.stream_id("bench");
  sample.width(static_cast<uint32_t>(c.width));
  sample.height(static_cast<uint32_t>(c.height));
  sample.encoding(c.channels == 3 ? msg::Encoding::BGR8 : msg::Encoding::MONO8);
  sample.data().assign(static_cast<size_t>(c.width) * c.height * c.channels, 0);
  for (size_t i = 0; i < sample.data().size(); i += 4096) sample.data()[i] = static_cast<uint8_t>(i);
  int refused = 0;
  const auto start = Clock::now();
  for (int i = 1; i <= frames; ++i) {
    if (c.rate_hz > 0) std::this_thread::sleep_until(start + std::chrono::nanoseconds(static_cast<int64_t>((i - 1) * 1e9 / c.rate_hz)));
    sample.frame_index(i);
    const bool ok = c.mode == "lossless" ? writer->write_reliably(sample) : writer->write(sample);
    if (!ok) ++refused;
  }
  writer->flush(std::chrono::seconds(10));
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  msg::Frame eos;
  eos.stream_id("bench");
  eos.end_of_stream(true);
  writer->write_reliably(eos, std::chrono::seconds(10));
  writer->flush(std::chrono::seconds(10));
  int status = 0;
  ::waitpid(child, &status, 0);
  std::ifstream in(out_file);
  nlohmann::json sub = nlohmann::json::parse(in, nullptr, false);
  std::remove(out_file.c_str());
  if (sub.is_discarded()) {
    result["error"] = "subscriber printed no result";
    return result;
  }
  const double received = sub["received"].get<double>();
  result["transport"] = c.transport;
  result["mode"] = c.mode;
  result["rate_hz"] = c.rate_hz;
  result["frame_mb"] = static_cast<double>(sample.data().size()) / 1e6;
  result["sent"] = frames;
  result["refused_writes"] = refused;
  result["received"] = received;
  result["loss_pct"] = 100.0 * (frames - received) / frames;
  result["latency_median_ms"] = sub["latency_median_ms"];
  result["latency_p99_ms"] = sub["latency_p99_ms"];
  result["throughput_fps"] = received / seconds;
  result["throughput_mb_s"] = sub["bytes"].get<double>() / 1e6 / seconds;
  return result;
}

double in_process_copy_ms(size_t bytes) {
  std::vector<uint8_t> a(bytes, 1), b(bytes);
  std::vector<double> times;
  for (int i = 0; i < 50; ++i) {
    const auto t0 = Clock::now();
    std::memcpy(b.data(), a.data(), bytes);
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    a[static_cast<size_t>(i)] = b[static_cast<size_t>(i) + 1];  // keep the copy observable
  }
  return percentile(times, 0.5);
}

int bench_main(int argc, char** argv) {
  std::string role = "pub", transport = "local", mode = "live", json_out;
  int domain = 60, frames = 150;
  return run_app(argc, argv, "bench-frame-hop", "benchmark: frame latency/throughput between two processes", [&](CLI::App& app) {
    app.add_option("--role", role)->check(CLI::IsMember({"pub", "sub"}));
    app.add_option("--transport", transport);
    app.add_option("--mode", mode);
    app.add_option("--domain", domain);
    app.add_option("--frames", frames, "frames per case")->capture_default_str();
    app.add_option("--json", json_out, "write all results as JSON");
    return [&]() -> int {
      init_logging("bench", "warn");
      if (role == "sub") return run_subscriber(transport, mode, domain);
      const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
      std::vector<Case> cases;
      for (auto [name, w, h, ch] : {std::tuple{"1080p mono8", 1920, 1080, 1}, std::tuple{"4K bgr8", 3840, 2160, 3}}) {
        for (const std::string t : {"local", "udp"}) {
          for (double rate : {30.0, 60.0}) cases.push_back({name, w, h, ch, t, "live", rate});
          cases.push_back({name, w, h, ch, t, "lossless", 0.0});
        }
      }
      nlohmann::json all = nlohmann::json::array();
      fmt::print("{:<12} {:<6} {:<9} {:>6} {:>6} {:>8} {:>10} {:>9} {:>8} {:>8}\n", "frame", "link", "mode", "rate", "sent",
                 "loss%", "median ms", "p99 ms", "fps", "MB/s");
      for (size_t i = 0; i < cases.size(); ++i) {
        const auto& c = cases[i];
        auto r = run_case(c, frames, domain + static_cast<int>(i), self);
        r["copy_ms"] = in_process_copy_ms(static_cast<size_t>(c.width) * c.height * c.channels);
        all.push_back(r);
        if (r.contains("error")) {
          fmt::print("{:<12} {:<6} {:<9} error: {}\n", c.name, c.transport, c.mode, r["error"].get<std::string>());
          continue;
        }
        fmt::print("{:<12} {:<6} {:<9} {:>6} {:>6} {:>8.1f} {:>10.2f} {:>9.2f} {:>8.1f} {:>8.0f}   (in-process copy {:.2f} ms)\n",
                   c.name, c.transport, c.mode, c.rate_hz > 0 ? fmt::format("{:.0f}", c.rate_hz) : "max", frames,
                   r["loss_pct"].get<double>(), r["latency_median_ms"].get<double>(), r["latency_p99_ms"].get<double>(),
                   r["throughput_fps"].get<double>(), r["throughput_mb_s"].get<double>(), r["copy_ms"].get<double>());
      }
      if (!json_out.empty()) std::ofstream(json_out) << all.dump(2) << "\n";
      return 0;
    };
  });
}

}  // namespace
}  // namespace uavmot

int main(int argc, char** argv) { return uavmot::bench_main(argc, argv); }
