#include "gcode/objects/object_label.hpp"

#include <cstdlib>


namespace gcode {

namespace {

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// "NAME id:3 copy 1": the name, and the id with the copy when it is not 0.
void split_prusa(std::string_view rest, LabelEvent& e) {
  e.key = std::string(rest);
  const std::size_t at = rest.rfind(" id:");
  if (at == std::string_view::npos) {
    e.name = std::string(rest);
    return;
  }
  e.name = std::string(trimmed(rest.substr(0, at)));
  std::string_view tail = rest.substr(at + 4);
  const std::size_t copy = tail.find(" copy ");
  std::string_view id = trimmed(tail.substr(0, copy));
  e.id = std::string(id);
  if (copy != std::string_view::npos) {
    std::string_view c = trimmed(tail.substr(copy + 6));
    if (!c.empty() && c != "0") e.id += "." + std::string(c);
  }
}

// Klipper's POLYGON=[[x,y],[x,y],...].
Polygon parse_polygon(std::string_view text) {
  Polygon out;
  std::string s(text);
  const char* p = s.c_str();
  while (*p != '\0') {
    while (*p != '\0' && *p != '-' && *p != '.' && (*p < '0' || *p > '9')) ++p;
    if (*p == '\0') break;
    char* end = nullptr;
    double x = std::strtod(p, &end);
    p = end;
    while (*p == ',' || *p == ' ') ++p;
    double y = std::strtod(p, &end);
    if (end == p) break;
    p = end;
    out.push_back({x, y});
  }
  return out;
}

}  // namespace

std::string_view dialect_name(LabelDialect d) {
  switch (d) {
    case LabelDialect::Prusa: return "PrusaSlicer";
    case LabelDialect::Cura: return "Cura";
    case LabelDialect::IdeaMaker: return "ideaMaker";
    case LabelDialect::Bambu: return "Bambu/Orca";
    case LabelDialect::Marlin: return "M486";
    case LabelDialect::Klipper: return "EXCLUDE_OBJECT";
    case LabelDialect::None: break;
  }
  return "none";
}

std::string klipper_argument(std::string_view arguments, std::string_view key) {
  std::size_t at = 0;
  while ((at = arguments.find(key, at)) != std::string_view::npos) {
    const bool word_start = at == 0 || arguments[at - 1] == ' ' || arguments[at - 1] == '\t';
    if (word_start && at + key.size() < arguments.size() && arguments[at + key.size()] == '=') break;
    at += key.size();
  }
  if (at == std::string_view::npos) return "";
  std::string_view v = arguments.substr(at + key.size() + 1);
  if (!v.empty() && (v.front() == '"' || v.front() == '\'')) {
    const std::size_t close = v.find(v.front(), 1);
    return std::string(v.substr(1, close == std::string_view::npos ? v.npos : close - 1));
  }
  if (!v.empty() && v.front() == '[') {
    int depth = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (v[i] == '[') ++depth;
      if (v[i] == ']' && --depth == 0) return std::string(v.substr(0, i + 1));
    }
    return std::string(v);
  }
  return std::string(v.substr(0, v.find_first_of(" \t")));
}

LabelEvent LabelReader::read(const Line& line) {
  if (line.kind == CommandKind::None) {
    if (line.comment.empty()) return {};
    return read_comment(line.comment_text());
  }
  if (line.is_m(486)) return read_m486(line);
  if (line.kind == CommandKind::Extended && starts_with(line.command, "EXCLUDE_OBJECT")) return read_klipper(line);
  return {};
}

LabelEvent LabelReader::accept(LabelEvent e) {
  if (e.kind == LabelKind::None) return e;
  const bool firmware = e.dialect == LabelDialect::Marlin || e.dialect == LabelDialect::Klipper;
  if (e.kind == LabelKind::Define && firmware && !firmware_declared_) {
    // The file declares firmware labels: they are the file's, whatever came first.
    firmware_declared_ = true;
    dialect_ = e.dialect;
  }
  if (dialect_ == LabelDialect::None && e.kind == LabelKind::Start) dialect_ = e.dialect;
  if (dialect_ != e.dialect && !(dialect_ == LabelDialect::None && e.kind == LabelKind::Define)) return {};
  return e;
}

LabelEvent LabelReader::read_comment(std::string_view text) {
  LabelEvent e;
  if (starts_with(text, "printing object ") || starts_with(text, "INIT printing object ")) {
    e.kind = LabelKind::Start;
    e.dialect = LabelDialect::Prusa;
    split_prusa(trimmed(text.substr(text.find("printing object ") + 16)), e);
    e.key = "p:" + e.key;
  } else if (starts_with(text, "stop printing object")) {
    e.kind = LabelKind::Stop;
    e.dialect = text.find("unique label id") != std::string_view::npos ? LabelDialect::Bambu : LabelDialect::Prusa;
  } else if (starts_with(text, "start printing object, unique label id:")) {
    e.kind = LabelKind::Start;
    e.dialect = LabelDialect::Bambu;
    e.id = std::string(trimmed(text.substr(39)));
    e.key = "b:" + e.id;
  } else if (starts_with(text, "MESH:")) {
    e.dialect = LabelDialect::Cura;
    std::string_view name = trimmed(text.substr(5));
    if (name == "NONMESH") {
      e.kind = LabelKind::NonObject;
    } else {
      e.kind = LabelKind::Start;
      e.name = std::string(name);
      e.key = "c:" + e.name;
    }
  } else if (starts_with(text, "PRINTING_ID:")) {
    e.dialect = LabelDialect::IdeaMaker;
    std::string_view id = trimmed(text.substr(12));
    if (id == "-1") {
      e.kind = LabelKind::NonObject;
    } else {
      e.kind = LabelKind::Start;
      e.id = std::string(id);
      e.name = idea_name_;
      e.key = "i:" + e.id;
    }
  } else if (starts_with(text, "PRINTING:")) {
    idea_name_ = std::string(trimmed(text.substr(9)));
  }
  return accept(std::move(e));
}

LabelEvent LabelReader::read_m486(const Line& line) {
  LabelEvent e;
  e.dialect = LabelDialect::Marlin;
  std::string_view code = line.code();
  // The words by hand: A"name" is a quoted string the word parser refuses.
  std::string name;
  const std::size_t quote = code.find('"');
  if (quote != std::string_view::npos) {
    const std::size_t close = code.find('"', quote + 1);
    name = std::string(code.substr(quote + 1, close == std::string_view::npos ? code.npos : close - quote - 1));
    code = code.substr(0, quote);
  }
  auto word = [&](char letter, std::string& value) {
    for (std::size_t i = 4; i < code.size(); ++i) {
      if ((code[i] == letter || code[i] == letter + 32) && (code[i - 1] == ' ' || code[i - 1] == '\t')) {
        std::size_t end = code.find_first_of(" \t", i);
        value = std::string(code.substr(i + 1, end == std::string_view::npos ? code.npos : end - i - 1));
        return true;
      }
    }
    return false;
  };
  std::string value;
  if (word('T', value)) {
    e.kind = LabelKind::Define;
  } else if (word('S', value)) {
    if (!value.empty() && value.front() == '-') {
      e.kind = LabelKind::NonObject;
    } else {
      e.kind = LabelKind::Start;
      e.id = value;
      e.name = name;
      e.key = "m:" + value;
    }
  }
  return accept(std::move(e));
}

LabelEvent LabelReader::read_klipper(const Line& line) {
  LabelEvent e;
  e.dialect = LabelDialect::Klipper;
  std::string_view cmd = line.command;
  std::string name = klipper_argument(line.argument, "NAME");
  if (cmd == "EXCLUDE_OBJECT_DEFINE" && !name.empty()) {
    e.kind = LabelKind::Define;
    e.name = name;
    e.key = "k:" + name;
    e.polygon = parse_polygon(klipper_argument(line.argument, "POLYGON"));
  } else if (cmd == "EXCLUDE_OBJECT_START" && !name.empty()) {
    e.kind = LabelKind::Start;
    e.name = name;
    e.key = "k:" + name;
  } else if (cmd == "EXCLUDE_OBJECT_END") {
    e.kind = LabelKind::Stop;
  }
  return accept(std::move(e));
}

}  // namespace gcode
