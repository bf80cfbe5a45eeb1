#include "gcode/core/layer_range.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>

#include "gcode/core/number.hpp"

namespace gcode {

namespace {

int parse_layer(std::string_view s, std::string_view whole) {
  int v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || p != s.data() + s.size() || v < 1)
    throw std::invalid_argument("bad layer range '" + std::string(whole) + "': '" + std::string(s) +
                                "' is not a layer number (layers count from 1)");
  return v;
}

}  // namespace

LayerRange LayerRange::parse(std::string_view text) {
  LayerRange r;
  r.text_ = std::string(text);
  if (text.empty()) throw std::invalid_argument("empty layer range");
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t comma = text.find(',', pos);
    if (comma == std::string_view::npos) comma = text.size();
    std::string_view part = text.substr(pos, comma - pos);
    if (part.empty()) throw std::invalid_argument("bad layer range '" + r.text_ + "': empty part");
    std::size_t dash = part.find('-');
    if (dash == std::string_view::npos) {
      int v = parse_layer(part, text);
      r.spans_.push_back({v, v, false});
    } else if (dash == 0) {
      r.spans_.push_back({parse_layer(part.substr(1), text), 0, true});
    } else {
      int first = parse_layer(part.substr(0, dash), text);
      std::string_view rest = part.substr(dash + 1);
      int last = rest.empty() ? 0 : parse_layer(rest, text);
      if (last != 0 && last < first)
        throw std::invalid_argument("bad layer range '" + r.text_ + "': " + std::string(part) + " runs backwards");
      r.spans_.push_back({first, last, false});
    }
    pos = comma + 1;
  }
  return r;
}

bool LayerRange::contains(int layer, int total) const {
  for (const Span& s : spans_) {
    if (s.from_end) {
      if (total > 0 && layer > total - s.first && layer <= total) return true;
    } else if (layer >= s.first && (s.last == 0 || layer <= s.last)) {
      return true;
    }
  }
  return false;
}

bool LayerRange::needs_total() const {
  for (const Span& s : spans_)
    if (s.from_end) return true;
  return false;
}

int LayerRange::highest_named() const {
  int h = 0;
  for (const Span& s : spans_)
    if (!s.from_end) h = std::max({h, s.first, s.last});
  return h;
}

int LayerRange::lowest(int total) const {
  int low = 0;
  for (const Span& s : spans_) {
    int first = s.from_end ? std::max(1, total - s.first + 1) : s.first;
    if (low == 0 || first < low) low = first;
  }
  return low;
}

ZRange ZRange::parse(std::string_view text) {
  ZRange z;
  auto colon = text.find(':');
  if (colon == std::string_view::npos)
    throw std::invalid_argument("bad Z range '" + std::string(text) + "': expected Z1:Z2");
  std::string_view a = text.substr(0, colon), b = text.substr(colon + 1);
  if (!a.empty() && !parse_number(a, z.low))
    throw std::invalid_argument("bad Z range '" + std::string(text) + "': '" + std::string(a) + "' is not a number");
  if (!b.empty() && !parse_number(b, z.high))
    throw std::invalid_argument("bad Z range '" + std::string(text) + "': '" + std::string(b) + "' is not a number");
  if (z.high < z.low) throw std::invalid_argument("bad Z range '" + std::string(text) + "': runs backwards");
  return z;
}

}  // namespace gcode
