#include "gcode/core/line_builder.hpp"

namespace gcode {

Precision::Precision() {
  for (int& d : decimals_) d = 3;
  decimals_['E' - 'A'] = 5;
  decimals_['F' - 'A'] = 0;
}

}  // namespace gcode
