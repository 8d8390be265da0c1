// Writes sample recordings of real uavmot topics for the official-reader check
// (tests/mcap_js/validate.mjs): CDR payloads exactly as Fast DDS puts them on the wire,
// schemas with the IDL text, one file per compression plus one recovered after a "crash".
// Also writes expected.json with the values serialized, for the reader to compare.
//
//   mcap_make_sample OUT_DIR IDL_DIR

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/core/error.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/mcap/idl_schema.hpp"
#include "uavmot/mcap/recover.hpp"
#include "uavmot/mcap/writer.hpp"

namespace {

using nlohmann::json;
using namespace uavmot;

constexpr int kFrames = 12;
constexpr uint64_t kStartNs = 1'700'000'000'000'000'000ull;
constexpr uint64_t kPeriodNs = 33'333'333;

uavmot::msg::TrackList make_tracks(int i, json& expected) {
  uavmot::msg::TrackList list;
  list.stream_id("clif-sample");
  list.frame_index(i + 1);
  list.capture_time_ns(static_cast<int64_t>(kStartNs + i * kPeriodNs));
  list.end_of_stream(i == kFrames - 1);
  json tracks = json::array();
  for (int t = 0; t < 2; ++t) {
    uavmot::msg::Track track;
    track.id(static_cast<uint64_t>(t + 1));
    track.state(t == 0 ? uavmot::msg::CONFIRMED : uavmot::msg::TENTATIVE);
    uavmot::msg::OrientedBox box;
    box.cx(100.5 + i * 2.0 + t * 300);
    box.cy(200.25 - i * 0.5);
    box.width(9.5);
    box.length(21.0 + t);
    box.angle_deg(-30.0 + i);
    track.box(box);
    track.vx(2.0);
    track.vy(-0.5);
    track.sigma_x(0.75);
    track.sigma_y(0.75);
    track.sigma_width(0.125);
    track.sigma_length(0.25);
    track.sigma_angle_deg(1.5);
    track.age(static_cast<uint32_t>(i + 1));
    track.frames_since_update(static_cast<uint32_t>(t));
    track.feature_ids({static_cast<uint64_t>(1000 + i), static_cast<uint64_t>(2000 + i), 9007199254740993ull});
    tracks.push_back({{"id", std::to_string(track.id())},
                      {"state", static_cast<int>(track.state())},
                      {"box", {{"cx", box.cx()}, {"cy", box.cy()}, {"width", box.width()}, {"length", box.length()},
                               {"angle_deg", box.angle_deg()}}},
                      {"vx", track.vx()},
                      {"sigma_angle_deg", track.sigma_angle_deg()},
                      {"age", track.age()},
                      {"frames_since_update", track.frames_since_update()},
                      {"feature_ids", {std::to_string(1000 + i), std::to_string(2000 + i), "9007199254740993"}}});
    list.tracks().push_back(track);
  }
  expected = {{"stream_id", list.stream_id()},
              {"frame_index", std::to_string(list.frame_index())},
              {"capture_time_ns", std::to_string(list.capture_time_ns())},
              {"end_of_stream", list.end_of_stream()},
              {"tracks", tracks}};
  return list;
}

uavmot::msg::Frame make_frame(int i, json& expected) {
  uavmot::msg::Frame frame;
  frame.stream_id("clif-sample");
  frame.frame_index(i + 1);
  frame.capture_time_ns(static_cast<int64_t>(kStartNs + i * kPeriodNs));
  frame.width(16);
  frame.height(8);
  frame.encoding(uavmot::msg::MONO8);
  frame.end_of_stream(false);
  std::vector<uint8_t> pixels(16 * 8);
  for (size_t k = 0; k < pixels.size(); ++k) pixels[k] = static_cast<uint8_t>(k * 3 + i);
  frame.data(pixels);
  expected = {{"stream_id", frame.stream_id()}, {"frame_index", std::to_string(frame.frame_index())},
              {"width", frame.width()},         {"height", frame.height()},
              {"encoding", static_cast<int>(frame.encoding())}, {"data", pixels}};
  return frame;
}

uavmot::msg::MotionEstimate make_motion(int i, json& expected) {
  uavmot::msg::MotionEstimate m;
  m.stream_id("clif-sample");
  m.frame_index(i + 1);
  m.capture_time_ns(static_cast<int64_t>(kStartNs + i * kPeriodNs));
  std::array<double, 9> h = {1.0, 0.0, 1.5 + i, 0.0, 1.0, -0.25, 0.0, 0.0, 1.0};
  m.homography(h);
  m.valid(true);
  m.inliers(static_cast<uint32_t>(400 + i));
  m.residual_px(0.375);
  m.end_of_stream(false);
  uavmot::msg::Feature f;
  f.id(77);
  f.x(10.5);
  f.y(20.5);
  f.vx(0.5);
  f.vy(-1.0);
  f.velocity_sigma(0.25);
  f.age(3);
  f.moving(i % 2 == 0);
  m.features().push_back(f);
  expected = {{"frame_index", std::to_string(m.frame_index())},
              {"homography", h},
              {"valid", true},
              {"inliers", m.inliers()},
              {"residual_px", m.residual_px()},
              {"features", {{{"id", "77"}, {"x", 10.5}, {"moving", f.moving()}}}}};
  return m;
}

struct Topic {
  std::string name;
  std::string type;
  std::string idl_file;
};

void write_sample(const std::string& path, mcap::Compression compression, const std::string& idl_dir, json& expected,
                  int crash_after_frames = -1, const std::string& crash_copy = "") {
  mcap::WriterOptions options;
  options.compression = compression;
  options.chunk_size = 2048;  // several chunks even for this small sample
  mcap::Writer writer(options);
  writer.open(path);
  const Topic topics[] = {{"uavmot/tracks", "uavmot::msg::TrackList", "tracks.idl"},
                          {"uavmot/frames", "uavmot::msg::Frame", "frame.idl"},
                          {"uavmot/motion", "uavmot::msg::MotionEstimate", "motion.idl"}};
  uint16_t channels[3];
  for (int t = 0; t < 3; ++t) {
    const std::string idl = mcap::flatten_idl(idl_dir + "/" + topics[t].idl_file);
    const uint16_t schema = writer.add_schema(topics[t].type, "omgidl", idl);
    channels[t] = writer.add_channel(schema, topics[t].name, "cdr",
                                     {{"topic", topics[t].name},
                                      {"type", topics[t].type},
                                      {"reliability", "RELIABLE"},
                                      {"durability", "VOLATILE"},
                                      {"history", "KEEP_LAST"},
                                      {"depth", "10"}});
  }
  expected = json::object();
  for (const Topic& t : topics) expected["topics"][t.name] = {{"type", t.type}, {"messages", json::array()}};
  for (int i = 0; i < kFrames; ++i) {
    const uint64_t t = kStartNs + i * kPeriodNs;
    json e;
    auto frame = make_frame(i, e);
    auto bytes = uavmot::dds::to_cdr<uavmot::msg::FramePubSubType>(frame);
    writer.write(channels[1], static_cast<uint32_t>(i), t, t + 1000, bytes.data(), bytes.size());
    expected["topics"]["uavmot/frames"]["messages"].push_back(e);
    auto motion = make_motion(i, e);
    bytes = uavmot::dds::to_cdr<uavmot::msg::MotionEstimatePubSubType>(motion);
    writer.write(channels[2], static_cast<uint32_t>(i), t + 5'000'000, t + 5'001'000, bytes.data(), bytes.size());
    expected["topics"]["uavmot/motion"]["messages"].push_back(e);
    auto tracks = make_tracks(i, e);
    bytes = uavmot::dds::to_cdr<uavmot::msg::TrackListPubSubType>(tracks);
    writer.write(channels[0], static_cast<uint32_t>(i), t + 9'000'000, t + 9'001'000, bytes.data(), bytes.size());
    expected["topics"]["uavmot/tracks"]["messages"].push_back(e);
    if (i + 1 == crash_after_frames) {
      writer.flush();  // the recorder's last complete chunk before it "crashes"
      std::filesystem::copy_file(writer.temporary_path(), crash_copy,
                                 std::filesystem::copy_options::overwrite_existing);
      expected["crash_after_frames"] = crash_after_frames;
    }
  }
  writer.close();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s OUT_DIR IDL_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::string out = argv[1];
    const std::string idl = argv[2];
    std::filesystem::create_directories(out);
    json manifest = json::object();
    const std::pair<const char*, mcap::Compression> kinds[] = {
        {"sample_none.mcap", mcap::Compression::None},
        {"sample_lz4.mcap", mcap::Compression::Lz4},
        {"sample_zstd.mcap", mcap::Compression::Zstd}};
    json expected;
    for (const auto& [name, compression] : kinds) {
      write_sample(out + "/" + name, compression, idl, expected);
      manifest["files"][name] = {{"compression", std::string(mcap::compression_name(compression))},
                                 {"frames", kFrames}, {"min_chunks", 2}};
    }
    manifest["expected"] = expected;

    // A recorder that crashed after 7 frames: its .tmp holds those 7 in complete chunks.
    json ignored;
    const std::string crashed = out + "/crashed.mcap.tmp";
    write_sample(out + "/full_for_crash.mcap", mcap::Compression::Zstd, idl, ignored, 7, crashed);
    const mcap::RecoverResult r = mcap::recover(crashed, out + "/sample_recovered.mcap");
    manifest["files"]["sample_recovered.mcap"] = {{"compression", "zstd"}, {"frames", 7}};
    std::filesystem::remove(out + "/full_for_crash.mcap");
    std::printf("recovered %llu messages from %s\n", static_cast<unsigned long long>(r.messages), crashed.c_str());

    std::FILE* f = std::fopen((out + "/expected.json").c_str(), "w");
    if (!f) throw InputError(out + "/expected.json: cannot write");
    const std::string text = manifest.dump(2);
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mcap_make_sample: %s\n", e.what());
    return 1;
  }
}
