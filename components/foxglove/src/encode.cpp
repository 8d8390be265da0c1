#include "uavmot/foxglove/encode.hpp"

#include "uavmot/mcap/cdr.hpp"

namespace uavmot::foxglove {
namespace {
using eprosima::fastcdr::Cdr;

// Upper bounds of the encoded sizes: each field's size plus its worst alignment padding.
constexpr size_t kHeader = 4;
constexpr size_t kTime = 8, kPoint = 16, kColor = 32, kAlign = 8, kLength = 4;
size_t string_bound(const std::string& s) { return kLength + s.size() + 1 + kAlign; }

void put(Cdr& cdr, const Time& t) { cdr.serialize(t.sec).serialize(t.nsec); }
void put(Cdr& cdr, const Point2& p) { cdr.serialize(p.x).serialize(p.y); }
void put(Cdr& cdr, const Color& c) { cdr.serialize(c.r).serialize(c.g).serialize(c.b).serialize(c.a); }

void put(Cdr& cdr, const CircleAnnotation& a);
void put(Cdr& cdr, const PointsAnnotation& a);
void put(Cdr& cdr, const TextAnnotation& a);

template <class T>
void put_sequence(Cdr& cdr, const std::vector<T>& items) {
  cdr.serialize(static_cast<uint32_t>(items.size()));
  for (const auto& item : items) put(cdr, item);
}

void put(Cdr& cdr, const CircleAnnotation& a) {
  put(cdr, a.timestamp);
  put(cdr, a.position);
  cdr.serialize(a.diameter).serialize(a.thickness);
  put(cdr, a.fill_color);
  put(cdr, a.outline_color);
}

void put(Cdr& cdr, const PointsAnnotation& a) {
  put(cdr, a.timestamp);
  cdr.serialize(static_cast<uint32_t>(a.type));  // IDL enums are 32-bit
  put_sequence(cdr, a.points);
  put(cdr, a.outline_color);
  put_sequence(cdr, a.outline_colors);
  put(cdr, a.fill_color);
  cdr.serialize(a.thickness);
}

void put(Cdr& cdr, const TextAnnotation& a) {
  put(cdr, a.timestamp);
  put(cdr, a.position);
  cdr.serialize(a.text);
  cdr.serialize(a.font_size);
  put(cdr, a.text_color);
  put(cdr, a.background_color);
}

void put_bytes(Cdr& cdr, const std::vector<uint8_t>& data) {
  cdr.serialize(static_cast<uint32_t>(data.size()));
  if (!data.empty()) cdr.serializeArray(data.data(), data.size());
}

}  // namespace

std::vector<uint8_t> encode(const ImageAnnotations& m) {
  size_t bound = kHeader + 3 * (kLength + kAlign);
  bound += m.circles.size() * (kTime + kPoint + 16 + 2 * kColor + kAlign);
  for (const auto& p : m.points) {
    bound += kTime + kLength + 2 * (kLength + kAlign) + p.points.size() * kPoint + p.outline_colors.size() * kColor +
             2 * kColor + 8 + kAlign;
  }
  for (const auto& t : m.texts) bound += kTime + kPoint + string_bound(t.text) + 8 + 2 * kColor + kAlign;
  return mcap::encode_cdr(bound, "foxglove::ImageAnnotations", [&](Cdr& cdr) {
    put_sequence(cdr, m.circles);
    put_sequence(cdr, m.points);
    put_sequence(cdr, m.texts);
  });
}

std::vector<uint8_t> encode(const CompressedImage& m) {
  const size_t bound = kHeader + kTime + string_bound(m.frame_id) + kLength + m.data.size() + string_bound(m.format);
  return mcap::encode_cdr(bound, "foxglove::CompressedImage", [&](Cdr& cdr) {
    put(cdr, m.timestamp);
    cdr.serialize(m.frame_id);
    put_bytes(cdr, m.data);
    cdr.serialize(m.format);
  });
}

std::vector<uint8_t> encode(const RawImage& m) {
  const size_t bound =
      kHeader + kTime + string_bound(m.frame_id) + 8 + string_bound(m.encoding) + 4 + kLength + m.data.size() + kAlign;
  return mcap::encode_cdr(bound, "foxglove::RawImage", [&](Cdr& cdr) {
    put(cdr, m.timestamp);
    cdr.serialize(m.frame_id);
    cdr.serialize(m.width).serialize(m.height);
    cdr.serialize(m.encoding);
    cdr.serialize(m.step);
    put_bytes(cdr, m.data);
  });
}

}  // namespace uavmot::foxglove
