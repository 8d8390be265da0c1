#pragma once
// IDL text for MCAP "omgidl" schemas. A schema's data must be self-contained (Foxglove's
// omgidl parser has no preprocessor), so included files are inlined.

#include <string>
#include <vector>

namespace uavmot::mcap {

// Reads the IDL file at `path` and replaces every `#include "file"` / `#include <file>` line by
// that file's text (resolved relative to the including file, else to each of `include_dirs` in
// turn, like `-I`; each file once, recursively). Throws InputError naming the file and line if an
// include cannot be read.
std::string flatten_idl(const std::string& path, const std::vector<std::string>& include_dirs = {});

}  // namespace uavmot::mcap
