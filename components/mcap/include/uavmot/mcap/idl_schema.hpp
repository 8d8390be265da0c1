#pragma once
// IDL text for MCAP "omgidl" schemas. A schema's data must be self-contained (Foxglove's
// omgidl parser has no preprocessor), so included files are inlined.

#include <string>

namespace uavmot::mcap {

// Reads the IDL file at `path` and replaces every `#include "file"` / `#include <file>` line by
// that file's text (resolved relative to the including file, each file once, recursively).
// Throws InputError naming the file and line if an include cannot be read.
std::string flatten_idl(const std::string& path);

}  // namespace uavmot::mcap
