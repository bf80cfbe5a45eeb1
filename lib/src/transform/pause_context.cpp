#include "gcode/transform/pause_context.hpp"

#include <algorithm>
#include <stdexcept>

namespace gcode {

void ParkRules::check() const {
  if (!given && !area.has_bed)
    throw std::runtime_error(
        "the file does not say how big the bed is, so the park position is unknown: "
        "give --park X,Y (or --bed WIDTHxDEPTH)");
}

Box2 ParkRules::print_box(const PauseContext& context) const {
  Box2 box;
  if (area.has_print_box) box.add(area.print_box);
  box.add(context.printed());
  return box;
}

void ParkRules::place(const PauseContext& context, const Precision& precision, PauseConfig& c) const {
  check();
  Box2 box = print_box(context);
  if (given) {
    c.park_x = x;
    c.park_y = y;
  } else {
    // The back of the bed, centred on the print (background.md §1).
    c.park_x = !box.empty() ? box.centre().x : area.bed.centre().x;
    c.park_y = area.bed.max_y - 10;
  }
  // A park position needs no more decimals than the file's own.
  c.park_x = Fixed::from_double(c.park_x).rounded(precision.of('X')).to_double();
  c.park_y = Fixed::from_double(c.park_y).rounded(precision.of('Y')).to_double();
  bool pushes = c.reload > 0 || c.purge > 0 || c.prime > 0;
  if (pushes && !box.empty() && box.contains(c.park_x, c.park_y))
    throw std::runtime_error("the park position X" + number_string(c.park_x, 3) + " Y" + number_string(c.park_y, 3) +
                             " is above the print (X " + number_string(box.min_x, 3) + ".." +
                             number_string(box.max_x, 3) + ", Y " + number_string(box.min_y, 3) + ".." +
                             number_string(box.max_y, 3) +
                             "): purging there would drop a blob on it; choose --park outside the print");
}

std::string ParkRules::place_or_lift(const PauseContext& context, const Precision& precision, PauseConfig& c) const {
  if (given || area.has_bed) {
    place(context, precision, c);
    return {};
  }
  c.park = false;
  std::string what =
      "no park position (the file does not say how big the bed is; give --park X,Y or --bed WIDTHxDEPTH): "
      "retract and lift where the head is";
  if (c.reload > 0 || c.purge > 0 || c.prime > 0) {
    // Above the part, pushed filament would drop on it.
    c.reload = c.purge = c.prime = 0;
    what += ", no reload, purge or prime above the print";
  }
  return what;
}

}  // namespace gcode
