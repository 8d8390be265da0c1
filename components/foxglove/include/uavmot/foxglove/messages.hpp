#pragma once
// The Foxglove schema messages uavmot writes, field for field as idl/foxglove/*.idl defines them
// (Foxglove's own OMG IDL). Plain structs; encode.hpp turns them into CDR.

#include <cstdint>
#include <string>
#include <vector>

namespace uavmot::foxglove {

struct Time {
  uint32_t sec = 0;
  uint32_t nsec = 0;
};
Time time_from_ns(int64_t ns);  // negative times clamp to 0

struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

struct Color {  // RGBA, each in [0, 1]
  double r = 1.0, g = 1.0, b = 1.0, a = 1.0;
};

struct CircleAnnotation {
  Time timestamp;
  Point2 position;
  double diameter = 0.0;
  double thickness = 0.0;
  Color fill_color;
  Color outline_color;
};

enum class PointsType : uint32_t { Unknown = 0, Points = 1, LineLoop = 2, LineStrip = 3, LineList = 4 };

struct PointsAnnotation {
  Time timestamp;
  PointsType type = PointsType::Unknown;
  std::vector<Point2> points;
  Color outline_color;
  std::vector<Color> outline_colors;
  Color fill_color;
  double thickness = 1.0;
};

struct TextAnnotation {
  Time timestamp;
  Point2 position;  // bottom-left of the text
  std::string text;
  double font_size = 12.0;
  Color text_color;
  Color background_color;
};

struct ImageAnnotations {
  std::vector<CircleAnnotation> circles;
  std::vector<PointsAnnotation> points;
  std::vector<TextAnnotation> texts;
};

struct CompressedImage {
  Time timestamp;
  std::string frame_id;
  std::vector<uint8_t> data;
  std::string format;  // "jpeg", "png"
};

struct RawImage {
  Time timestamp;
  std::string frame_id;
  uint32_t width = 0;
  uint32_t height = 0;
  std::string encoding;  // "mono8", "bgr8"
  uint32_t step = 0;
  std::vector<uint8_t> data;
};

}  // namespace uavmot::foxglove
