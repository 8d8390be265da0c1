#include "uavmot/segmentation/shadow_offset.hpp"

#include <algorithm>
#include <cmath>

namespace uavmot::segmentation {
namespace {

// Darkness (road level minus grey) summed by distance from one edge of the box, in bins of the
// candidate step: inside the box (depth from the edge) and outside it (distance beyond the edge).
struct EdgeBands {
  std::vector<double> inside, outside, inside_pixels;
  explicit EdgeBands(size_t bins) : inside(bins, 0.0), outside(bins, 0.0), inside_pixels(bins, 0.0) {}
};

// One axis of a box: the bands at its + and - ends, as sums over the first k bins.
struct AxisBands {
  EdgeBands plus, minus;
  explicit AxisBands(size_t bins) : plus(bins), minus(bins) {}

  void add(double coordinate, double half_extent, double darkness, double step) {
    const auto bins = static_cast<double>(plus.inside.size());
    auto bin = [&](double distance) { return static_cast<size_t>(std::min(bins - 1.0, std::floor(distance / step))); };
    const double beyond_plus = coordinate - half_extent, beyond_minus = -half_extent - coordinate;
    if (beyond_plus > 0.0) {
      if (beyond_plus < bins * step) plus.outside[bin(beyond_plus)] += darkness;
    } else if (-beyond_plus < bins * step) {
      plus.inside[bin(-beyond_plus)] += darkness;
      plus.inside_pixels[bin(-beyond_plus)] += 1.0;
    }
    if (beyond_minus > 0.0) {
      if (beyond_minus < bins * step) minus.outside[bin(beyond_minus)] += darkness;
    } else if (-beyond_minus < bins * step) {
      minus.inside[bin(-beyond_minus)] += darkness;
      minus.inside_pixels[bin(-beyond_minus)] += 1.0;
    }
  }

  // Running sums, so that band(k) is the sum of the first k bins.
  void accumulate() {
    for (std::vector<double>* v : {&plus.inside, &plus.outside, &plus.inside_pixels, &minus.inside, &minus.outside,
                                   &minus.inside_pixels}) {
      double sum = 0.0;
      for (double& x : *v) x = (sum += x);
    }
  }

  // What an offset t along this axis makes of the box's ends: the band inside the box at the far end
  // of t (its darkness and pixels) and the vote, that band's darkness less the band outside the
  // opposite end's. Bands are |t| rounded to whole bins wide; t of less than half a bin has none.
  struct Band {
    double vote = 0.0, darkness = 0.0, pixels = 0.0;
  };
  // Every band an offset can give, by its sign and its width in bins (0: none; wider than the
  // bins: all of them), listed once per box, so that each of its thousands of candidates is a lookup.
  struct Table {
    std::vector<Band> plus, minus;  // [k]: the band of an offset k bins wide
    const Band& band(double t, double step) const {
      const auto k = std::min(static_cast<size_t>(std::lround(std::abs(t) / step)), plus.size() - 1);
      return t > 0.0 ? plus[k] : minus[k];
    }
  };
  Table table() const {
    const size_t bins = plus.inside.size();
    Table t{std::vector<Band>(bins + 1), std::vector<Band>(bins + 1)};
    for (size_t k = 1; k <= bins; ++k) {
      const size_t i = k - 1;
      t.plus[k] = {plus.inside[i] - minus.outside[i], plus.inside[i], plus.inside_pixels[i]};
      t.minus[k] = {minus.inside[i] - plus.outside[i], minus.inside[i], minus.inside_pixels[i]};
    }
    return t;
  }
};

// At most this many candidates per side of zero: a long search (a fine GSD) takes coarser steps.
constexpr int kMaxHalf = 48;
ShadowOffsetOptions bounded(ShadowOffsetOptions o) {
  if (!(o.max_offset_px > 0.0) || !std::isfinite(o.max_offset_px)) o.max_offset_px = 0.0;
  o.step_px = std::max(o.step_px, o.max_offset_px / kMaxHalf);
  return o;
}
}  // namespace

ShadowOffset::ShadowOffset(ShadowOffsetOptions options)
    : options_(bounded(options)),
      half_(options_.step_px > 0.0 ? static_cast<int>(std::floor(options_.max_offset_px / options_.step_px)) : 0),
      score_(static_cast<size_t>((2 * half_ + 1) * (2 * half_ + 1)), 0.0), odd_(score_.size(), 0.0),
      band_darkness_(score_.size(), 0.0), band_pixels_(score_.size(), 0.0) {
  const double step = options_.step_px, reach = half_ * step;
  const int side = 2 * half_ + 1;
  for (int row = 0; row < side; ++row) {
    for (int col = 0; col < side; ++col) {
      const double sx = (col - half_) * step, sy = (row - half_) * step;
      if (std::hypot(sx, sy) > reach) continue;
      candidates_.push_back({static_cast<size_t>(row * side + col), sx, sy});
    }
  }
}

void ShadowOffset::reset() {
  std::fill(score_.begin(), score_.end(), 0.0);
  std::fill(odd_.begin(), odd_.end(), 0.0);
  std::fill(band_darkness_.begin(), band_darkness_.end(), 0.0);
  std::fill(band_pixels_.begin(), band_pixels_.end(), 0.0);
  votes_ = 0;
}

void ShadowOffset::observe(const cv::Mat& gray, cv::Point origin, const OrientedBox& box) {
  if (half_ == 0 || gray.type() != CV_8UC1 || !is_finite(box) || !(box.length > 1.0) || !(box.width > 1.0)) return;
  const double step = options_.step_px, reach = half_ * step;
  const double ring = reach + 1.0;  // the outside bands, and the road level read from them
  const double a = box.angle_deg * CV_PI / 180.0, ca = std::cos(a), sa = std::sin(a);
  const double half_l = box.length / 2.0, half_w = box.width / 2.0;
  OrientedBox grown = box, outer = box;
  grown.length += 2.0;
  grown.width += 2.0;
  outer.length += 2.0 * ring;
  outer.width += 2.0 * ring;
  const cv::Rect window(origin, gray.size());
  if ((pixel_bounds(grown) & window) != pixel_bounds(grown)) return;  // the box itself is cut off
  // Beyond the window the outside bands are missing, which counts as road (no darkness).
  const cv::Rect scan = pixel_bounds(outer) & window;

  std::vector<Pixel>& pixels = pixels_;
  std::vector<double>& road = road_;
  std::vector<double>& body = body_;
  pixels.clear();
  road.clear();
  body.clear();
  for (int y = scan.y; y < scan.br().y; ++y) {
    const uint8_t* row = gray.ptr<uint8_t>(y - origin.y);
    for (int x = scan.x; x < scan.br().x; ++x) {
      const double dx = x - box.cx, dy = y - box.cy;
      const double u = dx * ca + dy * sa, v = -dx * sa + dy * ca;
      if (std::abs(u) > half_l + ring || std::abs(v) > half_w + ring) continue;
      const double grey = row[x - origin.x];
      if (std::abs(u) <= half_l && std::abs(v) <= half_w) body.push_back(grey);
      else road.push_back(grey);
      pixels.push_back({u, v, grey});
    }
  }
  if (road.size() < 8 || body.size() < 4) return;
  auto quantile = [](std::vector<double>& values, double q) {
    const auto k = static_cast<long>(q * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[static_cast<size_t>(k)];
  };
  const double road_level = quantile(road, 0.5);
  if (!(quantile(body, 0.75) > road_level + options_.bright_margin)) return;  // no bright body to cast against

  const auto bins = static_cast<size_t>(half_);
  AxisBands along(bins), across(bins);
  for (const Pixel& p : pixels) {
    const double darkness = road_level - p.grey;
    if (std::abs(p.v) <= half_w) along.add(p.u, half_l, darkness, step);
    if (std::abs(p.u) <= half_l) across.add(p.v, half_w, darkness, step);
  }
  along.accumulate();
  across.accumulate();
  const AxisBands::Table along_bands = along.table(), across_bands = across.table();
  const bool odd = votes_ % 2 == 1;
  for (const Candidate& s : candidates_) {
    const double t_along = s.sx * ca + s.sy * sa, t_across = -s.sx * sa + s.sy * ca;
    // The body is what is left of the box: at least a pixel each way.
    if (std::abs(t_along) > box.length - 1.0 || std::abs(t_across) > box.width - 1.0) continue;
    const AxisBands::Band& a_band = along_bands.band(t_along, step);
    const AxisBands::Band& c_band = across_bands.band(t_across, step);
    const double vote = a_band.vote + c_band.vote;
    score_[s.cell] += vote;
    if (odd) odd_[s.cell] += vote;
    band_darkness_[s.cell] += a_band.darkness + c_band.darkness;
    band_pixels_[s.cell] += a_band.pixels + c_band.pixels;
  }
  ++votes_;
}

std::optional<cv::Vec2d> ShadowOffset::offset() const {
  if (votes_ < options_.min_regions || score_.empty()) return std::nullopt;
  // The cell of the best candidate by `score_at` (the first of equal maxima), or nothing when none
  // scores above zero.
  auto best = [&](auto score_at) -> std::optional<size_t> {
    size_t at = 0;
    for (size_t i = 1; i < score_.size(); ++i) {
      if (score_at(i) > score_at(at)) at = i;
    }
    return score_at(at) > 0.0 ? std::optional<size_t>(at) : std::nullopt;
  };
  const int side = 2 * half_ + 1;
  auto offset_of = [&](size_t cell) {
    const auto index = static_cast<int>(cell);
    return cv::Vec2d((index % side - half_) * options_.step_px, (index / side - half_) * options_.step_px);
  };
  const auto all = best([&](size_t i) { return score_[i]; });
  // A shadow is darker than the road: the best candidate's bands alone, on average over their pixels,
  // more than min_darkness grey levels. The vote also counts the band outside the other end, which a
  // bright body's blurred edge makes brighter than the road with no shadow at all (scenes rendered
  // without shadows: their bands averaged 12 grey levels brighter than the road, `paper`'s 4 darker).
  if (!all || !(band_darkness_[*all] > options_.min_darkness * band_pixels_[*all])) return std::nullopt;
  const auto even = best([&](size_t i) { return score_[i] - odd_[i]; });
  const auto odd = best([&](size_t i) { return odd_[i]; });
  if (!even || !odd || cv::norm(offset_of(*even) - offset_of(*odd)) > options_.agreement_px) return std::nullopt;
  // An offset of a step or two is what noise gives where there are no shadows (scenes rendered
  // without them: 0.25-0.35 px in a fifth of the frames), not a shadow to correct for.
  const cv::Vec2d offset = offset_of(*all);
  if (cv::norm(offset) < 2.0 * options_.step_px) return std::nullopt;
  return offset;
}

OrientedBox shrunk_by_shadow(const OrientedBox& blob, const cv::Vec2d& shadow) {
  const double a = blob.angle_deg * CV_PI / 180.0;
  const double along = std::abs(shadow[0] * std::cos(a) + shadow[1] * std::sin(a));
  const double across = std::abs(-shadow[0] * std::sin(a) + shadow[1] * std::cos(a));
  OrientedBox body = blob;
  body.length = std::max(blob.length - along, 0.5 * blob.length);
  body.width = std::max(blob.width - across, 0.5 * blob.width);
  return body;
}

}  // namespace uavmot::segmentation
