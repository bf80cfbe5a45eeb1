#pragma once
// The slicer's own print-time estimate written in a G-code file, the figure
// the estimator is compared with: PrusaSlicer's
// "; estimated printing time (normal mode) = 1h 14m 14s", CuraEngine's ";TIME:1764".
#include <cstdlib>
#include <string>
#include <string_view>

namespace gctest {

struct SlicerTime {
  bool found = false;
  bool cura = false;
  double seconds = 0;
};

inline SlicerTime slicer_time(std::string_view text) {
  SlicerTime t;
  constexpr std::string_view kPrusa = "; estimated printing time (normal mode) = ";
  if (std::size_t at = text.find(kPrusa); at != std::string_view::npos) {
    std::string value(text.substr(at + kPrusa.size(), text.find('\n', at) - at - kPrusa.size()));
    // "1d 2h 3m 4s", any part may be missing
    const char* p = value.c_str();
    while (*p) {
      char* end = nullptr;
      double n = std::strtod(p, &end);
      if (end == p) break;
      double unit = *end == 'd' ? 86400 : *end == 'h' ? 3600 : *end == 'm' ? 60 : 1;
      t.seconds += n * unit;
      p = *end ? end + 1 : end;
    }
    t.found = true;
    return t;
  }
  if (text.substr(0, 8) == ";FLAVOR:" || text.find("\n;TIME:") != std::string_view::npos) {
    std::size_t at = text.find("\n;TIME:");
    if (at != std::string_view::npos) {
      t.seconds = std::strtod(std::string(text.substr(at + 7, 20)).c_str(), nullptr);
      t.found = t.cura = true;
    }
  }
  return t;
}

}  // namespace gctest
