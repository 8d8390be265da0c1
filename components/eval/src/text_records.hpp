#pragma once
// Reading comma-separated text records with errors that name the file and line.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "uavmot/core/homography.hpp"

namespace uavmot::eval::detail {

struct Record {
  int line = 0;
  std::vector<std::string> fields;
};

// All non-empty lines split on commas (fields trimmed). Throws InputError if the file is missing.
std::vector<Record> read_records(const std::string& file);

// Strict number parsing: the whole field must be a finite number.
double parse_number(const std::string& file, const Record& record, size_t column, const char* name);
int64_t parse_integer(const std::string& file, const Record& record, size_t column, const char* name);

// Column indices by header name; `required` names must be present.
std::map<std::string, size_t> header_columns(const std::string& file, const Record& header,
                                             const std::vector<std::string>& required);

// frame,h11..h33 lines, frames in 1..length, normalised to h33 = 1.
std::map<int64_t, Homography> read_homographies(const std::string& file, int64_t length);

[[noreturn]] void fail(const std::string& file, int line, const std::string& message);

}  // namespace uavmot::eval::detail
