#pragma once
// Writes firmware labels for the objects of a plate, so that the firmware
// can cancel an object of a print from its own card: Klipper's
// EXCLUDE_OBJECT_DEFINE (name, centre, outline) before the first layer and
// EXCLUDE_OBJECT_START/END around each block, or Marlin's (and
// RepRapFirmware's) M486 T<count>, M486 S<n> with A"name" the first time,
// and M486 S-1 where a block ends. The blocks are those the slicer's labels
// give (object_tracker.hpp); every input line stays as it was.
#include <cstdint>
#include <string>
#include <vector>

#include "gcode/objects/object_table.hpp"
#include "gcode/objects/object_tracker.hpp"
#include "gcode/pipeline/stage.hpp"

namespace gcode {

enum class FirmwareLabels : std::uint8_t { Klipper, Marlin };

// Klipper's NAME= for each object: the name with every character other
// than letters, digits, '_', '-' and '.' made '_'; names two objects share
// get the id appended.
std::vector<std::string> klipper_names(const ObjectTable& table);

class LabelWriter : public Stage {
 public:
  // `table`: the plate's objects, read from the same input (a first pass).
  LabelWriter(const ObjectTable& table, FirmwareLabels kind);
  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override;

 private:
  void begin(int object, Emitter& out);
  void end(int object, Emitter& out);
  const ObjectTable& table_;
  FirmwareLabels kind_;
  std::vector<std::string> names_;
  std::vector<bool> named_;  // M486: the object's A"name" was written
  ObjectTracker tracker_;
  bool declared_ = false;
};

}  // namespace gcode
