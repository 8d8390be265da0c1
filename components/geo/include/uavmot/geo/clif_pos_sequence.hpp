#pragma once
// The POS records of a whole CLIF-style image folder: IMAGES/NAME.jpg has its record in
// IMAGES/../pos/NAME.txt (data/clif2007/jpg + data/clif2007/pos). The records' GPS times give the
// frame rate, which the images themselves do not carry. The GSD is not derivable from them: a
// POS record has position and attitude but no focal length or field of view (docs/geo.md).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include "uavmot/geo/clif_pos.hpp"

namespace uavmot::geo {

struct ClifPosSequence {
  std::filesystem::path pos_dir;
  std::vector<ClifPosRecord> records;  // in image name order, for the images that have one
  std::size_t images = 0;              // image files in the folder
  std::size_t missing = 0;             // images without a POS file
  // Median GPS time between consecutive records (only positive steps); nullopt below two records.
  std::optional<double> median_interval_s;
  std::optional<double> fps() const;   // 1 / median_interval_s
};

// nullopt when `image_folder` is not a folder or has no sibling `pos` folder with a record for
// any of its images. Throws InputError for a POS file that exists but does not parse.
std::optional<ClifPosSequence> read_clif_pos_sequence(const std::filesystem::path& image_folder);

}  // namespace uavmot::geo
