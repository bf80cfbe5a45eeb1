#include "gcode/objects/object_tracker.hpp"

namespace gcode {

int ObjectTracker::object(const LabelEvent& e) {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i].key == e.key) {
      ObjectName& n = names_[i];
      if (n.name.rfind("object ", 0) == 0 && !e.name.empty()) n.name = e.name;
      if (n.declared.empty()) n.declared = e.polygon;
      return static_cast<int>(i);
    }
  ObjectName n;
  n.key = e.key;
  n.id = e.id.empty() ? std::to_string(names_.size()) : e.id;
  n.name = e.name.empty() ? "object " + n.id : e.name;
  n.declared = e.polygon;
  names_.push_back(std::move(n));
  return static_cast<int>(names_.size() - 1);
}

int ObjectTracker::line(const Line& line) {
  changed_ = false;
  if (line.kind == CommandKind::None && line.comment.empty()) return current_;
  LabelEvent e = reader_.read(line);
  const int before = current_;
  switch (e.kind) {
    case LabelKind::None: break;
    case LabelKind::Start: current_ = object(e); break;
    case LabelKind::Stop:
    case LabelKind::NonObject: current_ = -1; break;
    case LabelKind::Define: if (!e.key.empty()) object(e); break;
  }
  changed_ = before != current_;
  return current_;
}

void ObjectTracker::layer() {
  if (reader_.dialect() == LabelDialect::Cura && current_ >= 0) {
    current_ = -1;
    changed_ = true;
  }
}

}  // namespace gcode
