#include "uavmot/mcap/idl_schema.hpp"

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "uavmot/core/error.hpp"

namespace uavmot::mcap {

namespace {

void append_flattened(const std::filesystem::path& file, const std::vector<std::string>& include_dirs,
                      std::set<std::filesystem::path>& seen, std::string& out) {
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(file);
  if (!seen.insert(canonical).second) return;
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot read IDL file", file.string()));
  static const std::regex include_line(R"(^\s*#\s*include\s*["<]([^">]+)[">].*$)");
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::smatch match;
    if (std::regex_match(line, match, include_line)) {
      std::filesystem::path included = file.parent_path() / match[1].str();
      for (auto dir = include_dirs.begin(); !std::filesystem::exists(included) && dir != include_dirs.end(); ++dir) {
        included = std::filesystem::path(*dir) / match[1].str();
      }
      if (!std::filesystem::exists(included)) {
        throw InputError(fmt::format("{}:{}: included IDL file {} not found", file.string(), number, included.string()));
      }
      append_flattened(included, include_dirs, seen, out);
      continue;
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string flatten_idl(const std::string& path, const std::vector<std::string>& include_dirs) {
  std::set<std::filesystem::path> seen;
  std::string out;
  append_flattened(path, include_dirs, seen, out);
  return out;
}

}  // namespace uavmot::mcap
