#include "uavmot/foxglove/schemas.hpp"

#include <filesystem>

#include "uavmot/core/error.hpp"
#include "uavmot/mcap/idl_schema.hpp"

namespace uavmot::foxglove {

std::string schema_text(const std::string& schema_name, const std::string& idl_dir) {
  const std::string prefix = "foxglove::";
  if (schema_name != kImageAnnotationsSchema && schema_name != kCompressedImageSchema && schema_name != kRawImageSchema) {
    throw InputError("'" + schema_name + "' is not a Foxglove schema uavmot writes");
  }
  const auto file = std::filesystem::path(idl_dir) / "foxglove" / (schema_name.substr(prefix.size()) + ".idl");
  // Foxglove's files include each other as "foxglove/X.idl", relative to idl/.
  return mcap::flatten_idl(file.string(), {idl_dir});
}

}  // namespace uavmot::foxglove
