#include "uavmot/core/result_files.hpp"

#include <cmath>
#include <filesystem>
#include <iterator>

#include <fmt/format.h>
#include <fmt/os.h>
#include <nlohmann/json.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/core/printed_number.hpp"
#include "result_files_resume.hpp"

namespace uavmot {
namespace {
// Fixed precision keeps files deterministic and diff-friendly; 3 decimals is 1/1000 px.
std::string mot_box_line(int64_t frame, int64_t id, const cv::Rect2d& r, double conf) {
  return fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},-1,-1,-1\n", frame, id, r.x, r.y, r.width, r.height, conf);
}

std::string region_line(int64_t frame, const PrintedRegion& r) {
  return fmt::format("{},-1,{},{},{},{},{},-1,-1,-1\n", frame, format_printed_fixed(r.x, 3), format_printed_fixed(r.y, 3),
                     format_printed_fixed(r.width, 3), format_printed_fixed(r.height, 3), format_printed_fixed(r.score, 3));
}
}  // namespace

PrintedRegion printed_region(const Region& region) {
  const cv::Rect2d r = axis_aligned_bounds(region.box);
  return {printed_fixed(r.x, 3), printed_fixed(r.y, 3), printed_fixed(r.width, 3), printed_fixed(r.height, 3),
          printed_fixed(region.score, 3)};
}

ResultFilesWriter::ResultFilesWriter(ResultFilesOptions options, PixelToLatLon pixel_to_lat_lon)
    : options_(std::move(options)), pixel_to_lat_lon_(std::move(pixel_to_lat_lon)) {
  std::error_code ec;
  std::filesystem::create_directories(options_.directory, ec);
  if (ec) throw InputError("cannot create output folder '" + options_.directory + "': " + ec.message());
  std::string obb_header = "frame,id,state,cx,cy,width,length,angle_deg,vx,vy";
  if (options_.gsd_m > 0.0) obb_header += ",cx_m,cy_m,width_m,length_m,speed_mps,speed_kmh";
  if (pixel_to_lat_lon_) obb_header += ",lat,lon";
  const std::string features_header = "frame,feature_id,x,y,vx,vy,moving";
  std::map<std::string, uint64_t> keep;  // file -> bytes kept of a continued run
  if (options_.resume) {
    const auto scan = detail::scan_for_resume(options_.directory, options_.resume_whole_frames,
                                              {{"tracks_obb.csv", obb_header}, {"features.csv", features_header}});
    keep = scan.keep_bytes;
    resumed_at_ = scan.point;
    frames_ = scan.frames;
    valid_homographies_ = scan.non_identity_homographies;
    confirmed_ids_ = scan.confirmed_ids;
  }
  tracks_ = open("tracks.txt", keep);
  tracks_obb_ = open("tracks_obb.csv", keep);
  if (tracks_obb_.bytes() == 0) tracks_obb_.append(obb_header + "\n");
  homographies_ = open("homographies.txt", keep);
  if (options_.write_features) {
    features_ = open("features.csv", keep);
    if (features_.bytes() == 0) features_.append(features_header + "\n");
  }
  if (options_.write_segmentation) {
    if (options_.write_clusters) clusters_ = open("clusters.txt", keep);
    regions_ = open("regions.txt", keep);
  }
}

ResultFilesWriter::~ResultFilesWriter() = default;

OutputFile ResultFilesWriter::open(const std::string& name, const std::map<std::string, uint64_t>& keep_bytes) {
  const std::string path = (std::filesystem::path(options_.directory) / name).string();
  const auto keep = keep_bytes.find(name);
  return keep == keep_bytes.end() ? OutputFile(path) : OutputFile(path, keep->second);
}

void ResultFilesWriter::write_motion(const MotionEstimate& motion) {
  if (closed_) throw std::logic_error("ResultFilesWriter used after close()");
  ++frames_;
  if (motion.quality.valid) ++valid_homographies_;
  Homography h = motion.homography;
  if (!normalize_homography(h)) h = identity_homography();
  if (options_.write_features) {
    fmt::memory_buffer lines;  // a frame's ~1 500 lines formatted in place, no string per line
    for (const auto& f : motion.features) {
      fmt::format_to(std::back_inserter(lines), "{},{},{:.3f},{:.3f},{:.4f},{:.4f},{}\n", motion.frame_index, f.id,
                     f.position.x, f.position.y, f.velocity[0], f.velocity[1], f.moving ? 1 : 0);
    }
    features_.append(std::string_view(lines.data(), lines.size()));
  }
  // Last: homographies.txt marks the frame's motion whole (a continued run cuts features.csv to it).
  std::string line = std::to_string(motion.frame_index);
  for (int i = 0; i < 9; ++i) line += fmt::format(",{:.10g}", h.val[i]);
  homographies_.append(line + "\n");
}

void ResultFilesWriter::write_segmentation(const SegmentationResult& segmentation) {
  if (closed_) throw std::logic_error("ResultFilesWriter used after close()");
  if (!options_.write_segmentation) return;
  if (options_.write_clusters) {
    std::string lines;
    for (const auto& c : segmentation.clusters) {
      lines += mot_box_line(segmentation.frame_index, -1, axis_aligned_bounds(c.box), static_cast<double>(c.feature_ids.size()));
    }
    clusters_.append(lines);
  }
  std::string lines;
  for (const auto& r : segmentation.regions) lines += region_line(segmentation.frame_index, printed_region(r));
  regions_.append(lines);
}

void ResultFilesWriter::write_printed_regions(int64_t frame_index, const std::vector<PrintedRegion>& regions) {
  if (closed_) throw std::logic_error("ResultFilesWriter used after close()");
  if (!options_.write_segmentation) return;
  std::string lines;
  for (const auto& r : regions) lines += region_line(frame_index, r);
  regions_.append(lines);
}

void ResultFilesWriter::write_tracks(const TrackList& tracks) {
  if (closed_) throw std::logic_error("ResultFilesWriter used after close()");
  std::string mot, obb;
  std::set<uint64_t> confirmed;
  for (const auto& t : tracks.tracks) {
    if (t.state == TrackState::Confirmed) {
      mot += mot_box_line(tracks.frame_index, static_cast<int64_t>(t.id), axis_aligned_bounds(t.box), 1.0);
      confirmed.insert(t.id);
    }
    obb += fmt::format("{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.4f},{:.4f}", tracks.frame_index, t.id,
                       to_string(t.state), t.box.cx, t.box.cy, t.box.width, t.box.length, t.box.angle_deg, t.velocity[0],
                       t.velocity[1]);
    if (options_.gsd_m > 0.0) {
      const double g = options_.gsd_m;
      const double speed_mps = std::hypot(t.velocity[0], t.velocity[1]) * g * options_.fps;
      obb += fmt::format(",{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.2f}", t.box.cx * g, t.box.cy * g, t.box.width * g,
                         t.box.length * g, speed_mps, speed_mps * 3.6);
    }
    if (pixel_to_lat_lon_) {
      // 7 decimals of a degree: about 1 cm, as in tracks.geojson; empty where the frame has no mapping.
      const auto ground = pixel_to_lat_lon_(tracks.frame_index, t.box.cx, t.box.cy);
      obb += (ground ? fmt::format(",{:.7f},{:.7f}", (*ground)[0], (*ground)[1]) : std::string(",,"));
    }
    obb += "\n";
  }
  tracks_.append(mot);
  tracks_obb_.append(obb);  // last: marks the frame's tracks whole
  confirmed_ids_.merge(confirmed);  // counted once written
}

void ResultFilesWriter::close(RunSummary summary) {
  if (closed_) return;
  closed_ = true;
  for (auto* file : {&tracks_, &tracks_obb_, &homographies_, &features_, &clusters_, &regions_}) file->close();
  summary.frames = frames_;
  summary.valid_homographies = valid_homographies_;
  summary.tracks_confirmed = confirmed_ids_.size();
  nlohmann::json j;
  j["input"] = summary.input;
  j["frames"] = summary.frames;
  j["valid_homographies"] = summary.valid_homographies;
  j["confirmed_tracks"] = summary.tracks_confirmed;
  j["wall_time_s"] = summary.wall_time_s;
  j["fps"] = summary.wall_time_s > 0.0 ? static_cast<double>(summary.frames) / summary.wall_time_s : 0.0;
  j["gsd_m"] = options_.gsd_m;
  if (!summary.gsd_source.empty()) j["gsd_source"] = summary.gsd_source;
  if (summary.metadata) {
    j["metadata"] = {{"packets", summary.metadata->packets},
                     {"standard", summary.metadata->standard},
                     {"bad_checksums", summary.metadata->bad_checksums},
                     {"frames_with_geometry", summary.metadata->frames_with_geometry}};
  }
  if (!summary.stage_mean_ms.empty()) j["stage_mean_ms"] = summary.stage_mean_ms;
  write_output_file((std::filesystem::path(options_.directory) / "summary.json").string(), j.dump(2) + "\n");
}

}  // namespace uavmot
