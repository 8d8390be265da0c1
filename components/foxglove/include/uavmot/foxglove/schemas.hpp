#pragma once
// The Foxglove schemas uavmot writes: their names (as Foxglove's panels recognise them) and their
// self-contained OMG IDL text for a channel's schema (idl/foxglove/, Foxglove's own files).

#include <string>

namespace uavmot::foxglove {

inline constexpr const char* kImageAnnotationsSchema = "foxglove::ImageAnnotations";
inline constexpr const char* kCompressedImageSchema = "foxglove::CompressedImage";
inline constexpr const char* kRawImageSchema = "foxglove::RawImage";

// The IDL text of one of the schemas above, includes inlined, read from `idl_dir`/foxglove/
// (`idl_dir`: uavmot's idl/ folder). Throws InputError for another name or a missing file.
std::string schema_text(const std::string& schema_name, const std::string& idl_dir);

}  // namespace uavmot::foxglove
