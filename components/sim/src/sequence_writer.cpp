#include "uavmot/sim/sequence_writer.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "uavmot/core/error.hpp"
#include "uavmot/sim/simulator.hpp"

namespace uavmot::sim {
namespace {
namespace fs = std::filesystem;

void make_dir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError("cannot create output folder '" + dir.string() + "': " + ec.message());
}

std::ofstream open_file(const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError("cannot write '" + path.string() + "'");
  return out;
}

void write_bytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out = open_file(path);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw InputError("cannot write '" + path.string() + "'");
}

std::string frame_name(int64_t index, const char* ext) { return fmt::format("{:06d}{}", index, ext); }

}  // namespace

WriteSummary write_sequence(const Scenario& scenario, uint64_t seed, const std::string& out_dir, const ProgressCallback& progress) {
  const fs::path root(out_dir);
  make_dir(root / "img1");
  make_dir(root / "gt" / "masks");
  const std::string name = root.filename().empty() ? root.parent_path().filename().string() : root.filename().string();

  Simulator sim(scenario, seed);
  std::ofstream gt = open_file(root / "gt" / "gt.txt");
  std::ofstream all = open_file(root / "gt" / "all_objects.txt");
  std::ofstream obb = open_file(root / "gt" / "gt_obb.csv");
  std::ofstream homographies = open_file(root / "gt" / "homographies.txt");
  // Only a world with structures gets gt/structures.csv (flat sequences stay as they were).
  const StructureParams& sp = scenario.structures;
  const bool with_structures = sp.building_density_per_ha > 0.0 || sp.tree_density_per_ha > 0.0 || sp.wall_density_per_ha > 0.0;
  std::ofstream structures;
  if (with_structures) {
    structures = open_file(root / "gt" / "structures.csv");
    structures << "frame,id,kind,height_m,bb_left,bb_top,bb_width,bb_height,outline\n";
  }
  obb << "frame,id,cx,cy,width,length,angle_deg,moving,parked,visibility,vx,vy\n";

  cv::VideoWriter video;
  const fs::path video_path = root / "video.mp4";
  if (scenario.sensor.write_video) {
    video.open(video_path.string(), cv::VideoWriter::fourcc('m', 'p', '4', 'v'), scenario.fps,
               cv::Size(scenario.camera.width, scenario.camera.height), false);
    if (!video.isOpened()) throw InputError("cannot open '" + video_path.string() + "' for writing (mp4v)");
  }

  WriteSummary summary;
  SimFrame frame;
  while (sim.next(frame)) {
    write_bytes(root / "img1" / frame_name(frame.index, ".jpg"), frame.encoded_jpeg);
    // 16-bit PNG id masks: ids beyond 65535 would wrap, so refuse them.
    cv::Mat mask16;
    double max_id = 0.0;
    cv::minMaxLoc(frame.object_id_mask, nullptr, &max_id);
    if (max_id > 65535) throw InputError("more than 65535 vehicles: the 16-bit id masks cannot hold them");
    frame.object_id_mask.convertTo(mask16, CV_16U);
    const std::string mask_path = (root / "gt" / "masks" / frame_name(frame.index, ".png")).string();
    if (!cv::imwrite(mask_path, mask16, {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE})) throw InputError("cannot write '" + mask_path + "'");

    homographies << frame.index;
    for (int i = 0; i < 9; ++i) homographies << fmt::format(",{:.17g}", frame.homography_from_previous.val[i]);
    homographies << "\n";
    for (const ObjectTruth& o : frame.objects) {
      const cv::Rect2d b = axis_aligned_bounds(o.box);
      const std::string box = fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.3f}", frame.index, o.id, b.x, b.y, b.width, b.height);
      if (o.moving) {
        gt << box << fmt::format(",1,1,{:.3f}\n", o.visibility);
        ++summary.moving_instances;
      }
      all << box << fmt::format(",{},{},{:.3f}\n", o.moving ? 1 : 0, o.parked ? 1 : 0, o.visibility);
      obb << fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{:.3f},{:.4f},{:.4f}\n", frame.index, o.id, o.box.cx,
                         o.box.cy, o.box.width, o.box.length, o.box.angle_deg, o.moving ? 1 : 0, o.parked ? 1 : 0,
                         o.visibility, o.velocity_px[0], o.velocity_px[1]);
    }
    for (const StructureTruth& st : frame.structures) {
      double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
      std::string outline;
      for (const cv::Point2d& p : st.outline) {
        x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
        outline += fmt::format("{}{:.2f} {:.2f}", outline.empty() ? "" : " ", p.x, p.y);
      }
      structures << fmt::format("{},{},{},{:.1f},{:.2f},{:.2f},{:.2f},{:.2f},{}\n", frame.index, st.id, structure_kind_name(st.kind),
                                st.height_m, x0, y0, x1 - x0, y1 - y0, outline);
    }
    if (video.isOpened()) video.write(frame.image);
    ++summary.frames;
    if (progress) progress(summary.frames, sim.frame_count());
  }
  video.release();
  for (std::ofstream* f : {&gt, &all, &obb, &homographies, &structures}) {
    if (!f->is_open()) continue;
    f->flush();
    if (!*f) throw InputError("writing ground truth in '" + (root / "gt").string() + "' failed");
  }
  summary.vehicles = sim.vehicles_seen();
  summary.moving_vehicles = sim.moving_vehicles_seen();
  summary.parked_vehicles = sim.parked_vehicles_seen();

  const SceneInfo scene = sim.scene();
  {
    std::ofstream ini = open_file(root / "seqinfo.ini");
    ini << "[Sequence]\n"
        << "name=" << name << "\n"
        << "imDir=img1\n"
        << "frameRate=" << fmt::format("{:g}", scenario.fps) << "\n"
        << "seqLength=" << summary.frames << "\n"
        << "imWidth=" << scenario.camera.width << "\n"
        << "imHeight=" << scenario.camera.height << "\n"
        << "imExt=.jpg\n"
        << "gsd=" << fmt::format("{:g}", scene.gsd_m) << "\n";
  }
  nlohmann::ordered_json meta;
  meta["generator"] = "uavmot-sim";
  meta["scenario"] = scenario.name;
  meta["seed"] = seed;
  meta["gsd_m"] = scene.gsd_m;
  meta["fps"] = scenario.fps;
  meta["frames"] = summary.frames;
  meta["width"] = scenario.camera.width;
  meta["height"] = scenario.camera.height;
  meta["vehicles"] = summary.vehicles;
  meta["moving_vehicles"] = summary.moving_vehicles;
  meta["parked_vehicles"] = summary.parked_vehicles;
  meta["moving_instances"] = summary.moving_instances;
  meta["files"] = {{"images", "img1/%06d.jpg"},
                   {"gt_moving", "gt/gt.txt"},
                   {"gt_all", "gt/all_objects.txt"},
                   {"gt_obb", "gt/gt_obb.csv"},
                   {"homographies", "gt/homographies.txt"},
                   {"masks", "gt/masks/%06d.png"},
                   {"structures", with_structures ? "gt/structures.csv" : ""},
                   {"video", scenario.sensor.write_video ? "video.mp4" : ""}};
  meta["scenario_yaml"] = scenario_to_yaml(scenario);
  std::ofstream meta_out = open_file(root / "meta.json");
  meta_out << meta.dump(2) << "\n";
  if (!meta_out) throw InputError("cannot write '" + (root / "meta.json").string() + "'");
  return summary;
}

}  // namespace uavmot::sim
