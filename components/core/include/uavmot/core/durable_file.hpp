#pragma once
// A file replaced atomically and durably: the saved states of the tracker, motion and segmentation
// (components/tracking/node/tracker_state_io.hpp, uavmot/core/state_ring.hpp),
// which a respawned component, or a new launch after the host lost power, restores.

#include <cstdint>
#include <string>
#include <vector>

namespace uavmot {

// Writes BYTES to PATH + ".tmp", fdatasyncs it, renames it over PATH and fsyncs PATH's folder, so
// PATH holds either its previous content or BYTES, never an empty or partial file, also after a
// power loss. Throws OutputError naming the file and the system's reason (no such folder, a full
// disk); PATH is then unchanged.
void write_file_durably(const std::string& path, const std::vector<uint8_t>& bytes);

}  // namespace uavmot
