#pragma once
// Topic names and QoS profile names: the DDS side of the IDL contract (docs/topics.md).

#include <string>

namespace uavmot::dds {

inline constexpr const char* kFramesTopic = "uavmot/frames";
inline constexpr const char* kMotionTopic = "uavmot/motion";
inline constexpr const char* kSegmentationTopic = "uavmot/segmentation";
inline constexpr const char* kTracksTopic = "uavmot/tracks";
inline constexpr const char* kHealthTopic = "uavmot/health";
inline constexpr const char* kTrackerStateTopic = "uavmot/tracker_state";
// What crosses the air -> ground link (idl/downlink.idl, docs/deployment.md): one sample per frame.
inline constexpr const char* kDownlinkResultsTopic = "uavmot/downlink/results";
// Optional JPEG preview of the frames (msg::Frame, encoding JPEG), paced by a flow controller.
inline constexpr const char* kDownlinkPreviewTopic = "uavmot/downlink/preview";

// lossless: nothing is dropped, slow readers hold back writers. live: newest sample wins.
enum class DeliveryMode { Lossless, Live };
DeliveryMode parse_delivery_mode(const std::string& name);  // "lossless" | "live"
const char* to_string(DeliveryMode mode);

// Preview: best effort, newest only, in either mode; it never holds anything back.
// ChainResume: a chain topic read by a component that restores its state after a restart (the
// tracker): in lossless mode its reader also gets the writer's recent history, so the samples
// published while it was down are not lost to it. Writers are the same as for Chain.
// FramesResume: the same for frames (the writer's last 16), for a respawned segmentation and a motion
// that restores its saved state.
enum class TopicClass { Frames, Chain, ChainResume, Downlink, Preview, Health, State, FramesResume };

// Names of the endpoint profiles in bringup/qos/uavmot_qos.xml, e.g. "frames_lossless_writer".
std::string writer_profile(TopicClass topic_class, DeliveryMode mode);
std::string reader_profile(TopicClass topic_class, DeliveryMode mode);

}  // namespace uavmot::dds
