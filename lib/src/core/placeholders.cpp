#include "gcode/core/placeholders.hpp"

namespace gcode {

std::string expand_placeholders(std::string_view text, const Placeholders& values) {
  std::string out;
  out.reserve(text.size());
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t open = text.find('{', pos);
    if (open == std::string_view::npos) break;
    std::size_t close = text.find('}', open);
    if (close == std::string_view::npos) break;
    std::string_view name = text.substr(open + 1, close - open - 1);
    const std::string* value = nullptr;
    for (const auto& [key, v] : values)
      if (key == name) value = &v;
    out.append(text.substr(pos, open - pos));
    if (value != nullptr) {
      out.append(*value);
      pos = close + 1;
    } else {
      out.push_back('{');
      pos = open + 1;
    }
  }
  out.append(text.substr(pos < text.size() ? pos : text.size()));
  return out;
}

bool has_placeholder(std::string_view text, std::string_view name) {
  for (std::size_t at = text.find('{'); at != std::string_view::npos; at = text.find('{', at + 1))
    if (text.substr(at + 1, name.size()) == name && text.substr(at + 1 + name.size(), 1) == "}") return true;
  return false;
}

}  // namespace gcode
