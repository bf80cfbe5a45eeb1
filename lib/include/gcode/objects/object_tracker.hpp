#pragma once
// Which object each line of a stream prints: the labels of the file
// (object_label.hpp) followed line by line, and every object the stream
// named so far, numbered in the order they first appear.
//
// The same tracker serves the table (object_table.hpp), the filter that
// leaves objects out (object_excluder.hpp) and gc-send's live cancel: the
// numbering depends only on the lines read, so a tracker that read a file
// once and another that reads it while it prints agree on every number.
#include <string>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/objects/object_label.hpp"

namespace gcode {

// An object as its labels name it.
struct ObjectName {
  std::string key;   // the label's identity (LabelEvent::key)
  std::string id;    // what users type: the slicer's number, else its place (0, 1, ...)
  std::string name;  // the slicer's name, else "object <id>"
  Polygon declared;  // Klipper's declared outline, if any
};

class ObjectTracker {
 public:
  // One line; returns the object it belongs to (an index into names()), or
  // -1 for none. A label line belongs to what it begins.
  int line(const Line& line);
  // A layer begins: Cura's mesh ends with its layer.
  void layer();
  int current() const { return current_; }
  // Whether the last line() changed the current object.
  bool changed() const { return changed_; }
  const std::vector<ObjectName>& names() const { return names_; }
  LabelDialect dialect() const { return reader_.dialect(); }
  // The index of the object with this key, registering it if new.
  int object(const LabelEvent& e);

 private:
  LabelReader reader_;
  std::vector<ObjectName> names_;
  int current_ = -1;
  bool changed_ = false;
};

}  // namespace gcode
