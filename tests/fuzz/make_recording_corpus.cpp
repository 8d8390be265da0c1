// Writes the recording target's seeds: tiny recordings of one stream as `uavmot record` writes
// them (uavmot/motion and uavmot/tracks channels with their omgidl schemas, CDR payloads), intact
// and as a crashed recorder leaves one (no summary).
//   fuzz_make_recording_corpus OUT_DIR

#include <cstdio>
#include <filesystem>
#include <string>

#include "motionPubSubTypes.h"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/mcap/writer.hpp"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/record/topic_catalog.hpp"

int main(int argc, char** argv) {
  using namespace uavmot;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1];
  std::filesystem::create_directories(out);
  const std::string idl_dir = record::find_idl_dir();
  auto channel = [&](mcap::Writer& writer, const std::string& topic) {
    const record::TopicSpec& spec = *record::find_topic(topic);
    return writer.add_channel(writer.add_schema(spec.type_name, "omgidl", record::schema_text(spec, idl_dir)), topic, "cdr",
                              record::channel_metadata(spec, dds::DeliveryMode::Lossless, {"RELIABLE", "VOLATILE", "KEEP_ALL", 0}));
  };
  for (const bool crashed : {false, true}) {
    mcap::WriterOptions options;
    options.compression = mcap::Compression::Lz4;
    options.chunk_size = 256;
    mcap::Writer writer(options);
    writer.open(out + (crashed ? "/tiny_crashed.mcap" : "/tiny.mcap"));
    const uint16_t motion_channel = channel(writer, "uavmot/motion");
    const uint16_t tracks_channel = channel(writer, "uavmot/tracks");
    msg::MotionEstimatePubSubType motion_type;
    msg::TrackListPubSubType tracks_type;
    for (int64_t k = 1; k <= 3; ++k) {
      MotionEstimate motion;
      motion.stream_id = "uav1";
      motion.frame_index = k;
      motion.image_width = 640;
      motion.image_height = 480;
      motion.homography = Homography(1, 0, 1.5, 0, 1, -0.5, 0, 0, 1);
      motion.quality = {true, 40, 0.3};
      motion.features = {{1, {10.5, 20.25}, {0.3, -0.1}, 0.02, 4, true}};
      auto m = dds::to_msg(motion);
      TrackList tracks;
      tracks.stream_id = "uav1";
      tracks.frame_index = k;
      Track track;
      track.id = 3;
      track.state = TrackState::Confirmed;
      track.box = {100.0 + static_cast<double>(k), 50, 4, 12, 10};
      track.velocity = {1.0, 0.0};
      tracks.tracks = {track};
      auto t = dds::to_msg(tracks);
      const uint64_t time = 1'000'000'000ull * static_cast<uint64_t>(k);
      const auto motion_cdr = dds::to_cdr(motion_type, m);
      const auto tracks_cdr = dds::to_cdr(tracks_type, t);
      writer.write(motion_channel, static_cast<uint32_t>(k), time, time, motion_cdr.data(), motion_cdr.size());
      writer.write(tracks_channel, static_cast<uint32_t>(k), time + 1, time + 1, tracks_cdr.data(), tracks_cdr.size());
    }
    if (crashed) {
      writer.flush();
      std::filesystem::copy_file(writer.temporary_path(), out + "/tiny_crashed_no_summary.partial",
                                 std::filesystem::copy_options::overwrite_existing);
    }
    writer.close();
    if (crashed) std::filesystem::remove(out + "/tiny_crashed.mcap");
  }
  return 0;
}
