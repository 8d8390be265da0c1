#include "uavmot/geo/clif_pos_sequence.hpp"

#include <algorithm>
#include <string>

namespace uavmot::geo {
namespace {
constexpr double kSecondsPerWeek = 7.0 * 24.0 * 3600.0;

bool is_image(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* known : {".jpg", ".jpeg", ".png", ".bmp", ".tif", ".tiff", ".pgm", ".ppm"}) {
    if (ext == known) return true;
  }
  return false;
}

// GPS time across week boundaries.
double gps_time_s(const ClifPosRecord& r) { return r.gps_week * kSecondsPerWeek + r.gps_seconds_of_week; }
}  // namespace

std::optional<double> ClifPosSequence::fps() const {
  if (!median_interval_s || *median_interval_s <= 0.0) return std::nullopt;
  return 1.0 / *median_interval_s;
}

std::optional<ClifPosSequence> read_clif_pos_sequence(const std::filesystem::path& image_folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(image_folder, ec)) return std::nullopt;
  // The folder's own name, so "jpg/" and "jpg" both find their sibling.
  const fs::path folder = fs::weakly_canonical(image_folder, ec);
  if (ec) return std::nullopt;
  ClifPosSequence out;
  out.pos_dir = folder.parent_path() / "pos";
  if (!fs::is_directory(out.pos_dir, ec)) return std::nullopt;

  std::vector<fs::path> images;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && is_image(entry.path())) images.push_back(entry.path());
  }
  std::sort(images.begin(), images.end());  // the frame source's order
  out.images = images.size();
  for (const fs::path& image : images) {
    const fs::path pos = out.pos_dir / (image.stem().string() + ".txt");
    if (!fs::is_regular_file(pos, ec)) {
      ++out.missing;
      continue;
    }
    out.records.push_back(read_clif_pos_file(pos));
  }
  if (out.records.empty()) return std::nullopt;

  std::vector<double> steps;
  for (std::size_t i = 1; i < out.records.size(); ++i) {
    const double dt = gps_time_s(out.records[i]) - gps_time_s(out.records[i - 1]);
    if (dt > 0.0) steps.push_back(dt);
  }
  if (!steps.empty()) {
    std::sort(steps.begin(), steps.end());
    const std::size_t n = steps.size();
    out.median_interval_s = n % 2 == 1 ? steps[n / 2] : 0.5 * (steps[n / 2 - 1] + steps[n / 2]);
  }
  return out;
}

}  // namespace uavmot::geo
