#include "text_records.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "uavmot/core/error.hpp"

namespace uavmot::eval::detail {
namespace {
std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}
}  // namespace

void fail(const std::string& file, int line, const std::string& message) {
  throw InputError(file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message);
}

std::vector<Record> read_records(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot open '" + file + "'");
  std::vector<Record> records;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (trim(line).empty()) continue;
    Record r;
    r.line = number;
    size_t start = 0;
    while (true) {
      const size_t comma = line.find(',', start);
      r.fields.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    records.push_back(std::move(r));
  }
  if (in.bad()) throw InputError("error reading '" + file + "'");
  return records;
}

double parse_number(const std::string& file, const Record& record, size_t column, const char* name) {
  if (column >= record.fields.size())
    fail(file, record.line, std::string("missing column ") + std::to_string(column + 1) + " (" + name + ")");
  const std::string& text = record.fields[column];
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    fail(file, record.line, std::string("column ") + std::to_string(column + 1) + " (" + name + ") is not a finite number: '" + text + "'");
  return value;
}

int64_t parse_integer(const std::string& file, const Record& record, size_t column, const char* name) {
  const double value = parse_number(file, record, column, name);
  if (value != std::floor(value) || std::abs(value) > 9e15)
    fail(file, record.line, std::string("column ") + std::to_string(column + 1) + " (" + name + ") is not an integer: '" +
                                record.fields[column] + "'");
  return static_cast<int64_t>(value);
}

std::map<std::string, size_t> header_columns(const std::string& file, const Record& header, const std::vector<std::string>& required) {
  std::map<std::string, size_t> columns;
  for (size_t i = 0; i < header.fields.size(); ++i) columns[header.fields[i]] = i;
  for (const auto& name : required)
    if (!columns.count(name)) fail(file, header.line, "header lacks the column '" + name + "'");
  return columns;
}

std::map<int64_t, Homography> read_homographies(const std::string& file, int64_t length) {
  std::map<int64_t, Homography> out;
  for (const auto& r : read_records(file)) {
    if (r.fields.size() != 10) fail(file, r.line, "expected 10 values: frame,h11,h12,h13,h21,h22,h23,h31,h32,h33");
    const int64_t frame = parse_integer(file, r, 0, "frame");
    if (frame < 1 || frame > length)
      fail(file, r.line, "frame " + std::to_string(frame) + " is outside the sequence (1.." + std::to_string(length) + ")");
    std::array<double, 9> v{};
    for (int i = 0; i < 9; ++i) v[i] = parse_number(file, r, static_cast<size_t>(i) + 1, "h");
    Homography h = from_row_major(v);
    if (!normalize_homography(h)) fail(file, r.line, "homography is degenerate (h33 = 0)");
    if (!out.emplace(frame, h).second) fail(file, r.line, "frame " + std::to_string(frame) + " given twice");
  }
  return out;
}

}  // namespace uavmot::eval::detail
