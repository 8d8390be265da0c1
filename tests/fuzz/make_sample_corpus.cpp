// Writes the sample_validators seeds: one real CDR sample of each chain topic, as the node's
// DataReader would receive it, behind the selector byte the target reads first.
//   fuzz_make_sample_corpus OUT_DIR

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "downlinkPubSubTypes.h"
#include "framePubSubTypes.h"
#include "motionPubSubTypes.h"
#include "segmentationPubSubTypes.h"
#include "tracker_statePubSubTypes.h"
#include "tracker_state_io.hpp"
#include "tracksPubSubTypes.h"
#include "uavmot/dds/cdr_sample.hpp"
#include "uavmot/dds/chain_convert.hpp"
#include "uavmot/dds/downlink_convert.hpp"
#include "uavmot/dds/frame_convert.hpp"

namespace {

template <class PubSubType>
void write(const std::string& path, uint8_t selector, typename PubSubType::type sample) {
  const std::vector<uint8_t> bytes = uavmot::dds::to_cdr<PubSubType>(sample);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.put(static_cast<char>(selector));
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace uavmot;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1];
  std::filesystem::create_directories(out);

  Frame frame{"uav1", 3, 120'000'000, cv::Mat(6, 8, CV_8UC1, cv::Scalar(7))};
  write<msg::FramePubSubType>(out + "/frame_mono8", 0, dds::to_msg(frame));
  frame.image = cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3));
  write<msg::FramePubSubType>(out + "/frame_bgr8", 0, dds::to_msg(frame));
  msg::Frame jpeg = dds::to_msg(frame);
  jpeg.encoding(msg::Encoding::JPEG);
  cv::imencode(".jpg", frame.image, jpeg.data());
  write<msg::FramePubSubType>(out + "/frame_jpeg", 0, jpeg);
  write<msg::FramePubSubType>(out + "/frame_end_of_stream", 0, dds::end_of_stream_frame("uav1", 3));

  MotionEstimate motion;
  motion.stream_id = "uav1";
  motion.frame_index = 3;
  motion.image_width = 64;
  motion.image_height = 48;
  motion.homography = Homography(1.01, 0.002, 1.5, -0.003, 0.99, -2.5, 1e-6, -2e-6, 1);
  motion.quality = {true, 40, 0.3};
  motion.features = {{1, {10.5, 20.25}, {0.3, -0.1}, 0.02, 4, true}, {2, {30, 5}, {0, 0}, 0.01, 9, false}};
  write<msg::MotionEstimatePubSubType>(out + "/motion", 1, dds::to_msg(motion));

  SegmentationResult segmentation;
  segmentation.stream_id = "uav1";
  segmentation.frame_index = 3;
  segmentation.clusters = {{4, {11.5, 22.5, 5.1, 15.2, -33.3}, {0.7, 0.1}, {1, 2}}};
  segmentation.regions = {{{11.25, 22.75, 5.0, 14.9, 89.9}, SegmentationMethod::Fusion, 0.875, 4}};
  write<msg::SegmentationPubSubType>(out + "/segmentation", 2, dds::to_msg(segmentation));

  TrackList tracks;
  tracks.stream_id = "uav1";
  tracks.frame_index = 3;
  Track track;
  track.id = 12;
  track.state = TrackState::Confirmed;
  track.box = {11.1, 22.2, 5.3, 15.4, -60};
  track.velocity = {1.5, -0.25};
  track.sigma_x = 0.3;
  track.age = 40;
  track.feature_ids = {1, 2};
  tracks.tracks = {track};
  write<msg::TrackListPubSubType>(out + "/tracks", 3, dds::to_msg(tracks));

  dds::FrameParts parts;
  parts.motion = motion;
  parts.segmentation = segmentation;
  parts.tracks = tracks;
  write<msg::FrameResultsPubSubType>(out + "/downlink_results", 4, dds::to_downlink_msg("uav1", 3, parts));

  tracking::TrackerState state;
  state.next_id = 13;
  tracking::TrackRecord record;
  record.id = 12;
  record.state = TrackState::Confirmed;
  record.mean = {11.1, 22.2, 5.3, 15.4, -60, 1.5, -0.25};
  for (int i = 0; i < tracking::kStateSize; ++i) record.covariance[i * tracking::kStateSize + i] = 1.0;
  record.anchor_box = track.box;
  record.age = 40;
  record.hits = 30;
  state.tracks = {record};
  write<msg::TrackerSnapshotPubSubType>(out + "/tracker_state", 5, tracking::to_msg(state, "uav1", 3));
  return 0;
}
