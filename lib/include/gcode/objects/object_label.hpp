#pragma once
// The words each slicer and firmware uses to say which object a stretch of
// G-code prints, read one line at a time:
//
//   PrusaSlicer, SuperSlicer, Slic3r  "; printing object NAME id:N copy C" ...
//                                     "; stop printing object ..." (SuperSlicer
//                                     also "; INIT printing object ...")
//   Cura                              ";MESH:NAME" until the next ";MESH:" or
//                                     layer; ";MESH:NONMESH" is no object
//   ideaMaker                         ";PRINTING: NAME" then ";PRINTING_ID: N"
//                                     (-1 with NON-OBJECT: no object)
//   Bambu Studio, OrcaSlicer          "; start printing object, unique label
//                                     id: N" ... "; stop printing object, ..."
//   Marlin, RepRapFirmware            M486 T (count), S<n> [A"name"] (start),
//                                     S-1 (no object)
//   Klipper                           EXCLUDE_OBJECT_DEFINE NAME= [CENTER=]
//                                     [POLYGON=], EXCLUDE_OBJECT_START/END NAME=
//
// A file may carry two of these at once (PrusaSlicer writes its comments
// and the firmware's labels): the firmware's labels win when the file
// declares them (DEFINE, M486 T), else the first kind that starts an
// object; the other kind's words are then ignored.
#include <cstdint>
#include <string>
#include <string_view>

#include "gcode/core/geometry.hpp"
#include "gcode/core/line.hpp"

namespace gcode {

enum class LabelDialect : std::uint8_t { None, Prusa, Cura, IdeaMaker, Bambu, Marlin, Klipper };

// The name users know a dialect by ("PrusaSlicer", "Cura", ...).
std::string_view dialect_name(LabelDialect d);

enum class LabelKind : std::uint8_t {
  None,       // the line says nothing about objects
  Start,      // an object's block begins after this line
  Stop,       // the current object's block ends here
  NonObject,  // what follows belongs to no object (Cura NONMESH, ideaMaker -1, M486 S-1)
  Define,     // an object is declared (Klipper DEFINE, M486 T): no block begins
};

struct LabelEvent {
  LabelKind kind = LabelKind::None;
  LabelDialect dialect = LabelDialect::None;
  std::string key;   // the object, the same for each of its blocks
  std::string id;    // the slicer's number for it ("3", "3.1" for copy 1), or "" (none given)
  std::string name;  // its name, or "" (none given)
  Polygon polygon;   // Klipper's POLYGON=, when given
};

class LabelReader {
 public:
  // One line of the input. Events of a dialect other than the file's are
  // reported as None.
  LabelEvent read(const Line& line);
  LabelDialect dialect() const { return dialect_; }

 private:
  LabelEvent read_comment(std::string_view text);
  LabelEvent read_m486(const Line& line);
  LabelEvent read_klipper(const Line& line);
  LabelEvent accept(LabelEvent e);
  LabelDialect dialect_ = LabelDialect::None;
  bool firmware_declared_ = false;
  std::string idea_name_;  // ideaMaker's ;PRINTING: name, until its ;PRINTING_ID:
};

// The words of Klipper's arguments: `NAME=value` (value up to a blank, or a
// quoted string, or a bracketed list), "" when absent.
std::string klipper_argument(std::string_view arguments, std::string_view key);

}  // namespace gcode
