#include "gcode/transform/splice_block.hpp"

#include <fmt/format.h>

#include <cmath>

#include "gcode/core/number.hpp"

namespace gcode {

std::string printer_difference(const PrintArea& input, const PrintArea& other, const std::string& other_name) {
  if (!input.has_bed || !other.has_bed) return {};
  auto same = [](double a, double b) { return std::fabs(a - b) < 0.5; };
  const Box2& a = input.bed;
  const Box2& b = other.bed;
  if (same(a.min_x, b.min_x) && same(a.min_y, b.min_y) && same(a.max_x, b.max_x) && same(a.max_y, b.max_y)) return {};
  char w[kMaxNumberChars], d[kMaxNumberChars], w2[kMaxNumberChars], d2[kMaxNumberChars];
  return fmt::format("{} was sliced for a {}x{} mm bed, the input for {}x{} mm: its moves are used as they are", other_name,
                     number_text(b.width(), 1, w), number_text(b.depth(), 1, d), number_text(a.width(), 1, w2),
                     number_text(a.depth(), 1, d2));
}

std::string placement_difference(const Box2& printed, const Box2& theirs, const std::string& their_name) {
  constexpr double kPlacement = 2.0;
  if (printed.empty() || theirs.empty()) return {};
  Point2 a = printed.centre(), b = theirs.centre();
  double d = std::hypot(a.x - b.x, a.y - b.y);
  if (d <= kPlacement) return {};
  char bx[kMaxNumberChars], by[kMaxNumberChars], ax[kMaxNumberChars], ay[kMaxNumberChars], dd[kMaxNumberChars];
  return fmt::format(
      "{} does not lie where the input prints: its part is centred at X{} Y{}, the input's at X{} Y{} ({} mm "
      "apart); slice it for the same printer and placement",
      their_name, number_text(b.x, 3, bx), number_text(b.y, 3, by), number_text(a.x, 3, ax), number_text(a.y, 3, ay),
      number_text(d, 1, dd));
}

SpliceBlock layer_index_block(const LayerIndex& index, int first, int last, bool through_end) {
  const IndexedLayer& l = index.layer(first);
  SpliceBlock b;
  b.fd = index.fd();
  b.name = index.name();
  b.markers = &index.markers();
  b.begin = l.info.offset;
  b.end = through_end ? std::uint64_t(-1) : index.layer(last).end;
  b.through_end = through_end;
  b.first_line = l.info.first_line;
  b.first_layer = l.info;
  b.start = index.point(first);
  return b;
}

// The block pipeline's one stage: rewrites the block's lines and hands them

}  // namespace gcode
