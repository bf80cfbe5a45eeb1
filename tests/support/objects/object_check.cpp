#include "objects/object_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace gctest {

namespace object_check {

struct Extrusion {
  double start[3];
  double end[3];
  double filament;
  double depth_before;
  bool fw_before;
  std::string object;  // "name|id" of its label, "" for none
  int layer;
};

bool starts(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// A value after a letter in the code part ("G1 X1.5" -> 1.5 for 'X').
bool word(std::string_view code, char letter, double& v) {
  for (std::size_t i = 1; i < code.size(); ++i) {
    if ((code[i] == letter) && (code[i - 1] == ' ' || code[i - 1] == '\t')) {
      std::string num(code.substr(i + 1, code.find_first_of(" \t", i) - i - 1));
      if (num.empty()) return false;
      char* end = nullptr;
      v = std::strtod(num.c_str(), &end);
      return end != num.c_str();
    }
  }
  return false;
}

class Replay {
 public:
  std::vector<Extrusion> extrusions;
  double pos[3] = {0, 0, 0};
  double e = 0, depth = 0;
  bool fw = false;

  void line(std::string_view raw) {
    std::string_view text = trim(raw);
    std::string_view comment;
    const std::size_t semi = text.find(';');
    if (semi != std::string_view::npos) {
      comment = trim(text.substr(semi + 1));
      text = trim(text.substr(0, semi));
    }
    if (!comment.empty() || !text.empty()) label(text, comment);
    if (text.empty()) return;
    std::string upper(text);
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    const std::string_view code = upper;
    const std::string_view cmd = code.substr(0, code.find(' '));
    if (cmd == "G90") rel_xyz_ = false, rel_e_ = follows_ ? false : rel_e_;
    if (cmd == "G91") rel_xyz_ = true, rel_e_ = follows_ ? true : rel_e_;
    if (cmd == "M82") rel_e_ = false, follows_ = true;
    if (cmd == "M83") rel_e_ = true, follows_ = true;
    if (cmd == "G20") inch_ = 25.4;
    if (cmd == "G21") inch_ = 1;
    if (cmd == "G92") {
      double v;
      const char axes[3] = {'X', 'Y', 'Z'};
      bool any = false;
      for (int a = 0; a < 3; ++a)
        if (word(code, axes[a], v)) pos[a] = v * inch_, any = true;
      if (word(code, 'E', v)) e = v * inch_, any = true;
      if (!any) pos[0] = pos[1] = pos[2] = 0, e = 0;
    }
    if ((cmd == "G10" || cmd == "G11") && code.size() == 3) fw = cmd == "G10";
    if (cmd == "G28") {
      const bool all = code.find_first_of("XYZ", 3) == std::string_view::npos;
      const char axes[3] = {'X', 'Y', 'Z'};
      for (int a = 0; a < 3; ++a)
        if (all || code.find(axes[a], 3) != std::string_view::npos) pos[a] = 0;
    }
    if (cmd == "G0" || cmd == "G1" || cmd == "G2" || cmd == "G3" || cmd == "G00" || cmd == "G01") move(code);
  }

 private:
  void label(std::string_view code, std::string_view c) {
    if (starts(c, "printing object ") || starts(c, "INIT printing object ")) {
      std::string_view rest = trim(c.substr(c.find("printing object ") + 16));
      const std::size_t at = rest.rfind(" id:");
      object_ = std::string(trim(rest.substr(0, at))) + "|";
      if (at != std::string_view::npos) {
        const std::size_t copy = rest.find(" copy ");
        object_ += std::string(trim(rest.substr(at + 4, copy - at - 4)));
        // Copies other than the first: "id.copy" (gc-objects(1) names them so).
        std::string_view c = copy == std::string_view::npos ? "0" : trim(rest.substr(copy + 6));
        if (c != "0") object_ += "." + std::string(c);
      }
    } else if (starts(c, "stop printing object")) {
      object_.clear();
    } else if (starts(c, "start printing object, unique label id:")) {
      object_ = "|" + std::string(trim(c.substr(39)));
    } else if (starts(c, "MESH:")) {
      object_ = trim(c.substr(5)) == "NONMESH" ? "" : std::string(trim(c.substr(5))) + "|";
    } else if (starts(c, "LAYER:") && cura_) {
      object_.clear();
    } else if (starts(c, "PRINTING:")) {
      idea_ = std::string(trim(c.substr(9)));
    } else if (starts(c, "PRINTING_ID:")) {
      std::string id(trim(c.substr(12)));
      object_ = id == "-1" ? "" : idea_ + "|" + id;
    }
    if (starts(c, "MESH:")) cura_ = true;
    if (starts(code, "EXCLUDE_OBJECT_START")) {
      std::size_t n = code.find("NAME=");
      object_ = std::string(code.substr(n + 5, code.find(' ', n) - n - 5)) + "|";
    } else if (starts(code, "EXCLUDE_OBJECT_END")) {
      object_.clear();
    } else if (starts(code, "M486")) {
      double s;
      if (word(code, 'S', s)) {
        std::string name;
        std::size_t q = code.find('"');
        if (q != std::string_view::npos) name = std::string(code.substr(q + 1, code.find('"', q + 1) - q - 1));
        object_ = s < 0 ? "" : name + "|" + std::to_string(static_cast<long>(s));
      }
    }
  }

  void move(std::string_view code) {
    double target[3] = {pos[0], pos[1], pos[2]};
    const char axes[3] = {'X', 'Y', 'Z'};
    double v;
    for (int a = 0; a < 3; ++a)
      if (word(code, axes[a], v)) target[a] = rel_xyz_ ? pos[a] + v * inch_ : v * inch_;
    double filament = 0;
    if (word(code, 'E', v)) {
      v *= inch_;
      filament = rel_e_ ? v : v - e;
      e = rel_e_ ? e + v : v;
    }
    const bool moves = target[0] != pos[0] || target[1] != pos[1] || target[2] != pos[2];
    if (moves && filament > 0) {
      if (target[2] > top_ + 1e-6) {
        top_ = target[2];
        ++layer_;
      }
      extrusions.push_back({{pos[0], pos[1], pos[2]}, {target[0], target[1], target[2]}, filament, depth, fw, object_, layer_});
      depth = 0;
    } else if (filament != 0) {
      depth = std::max(0.0, depth - filament);
    }
    std::copy(target, target + 3, pos);
  }

  bool rel_xyz_ = false, rel_e_ = false, follows_ = true, cura_ = false;
  double inch_ = 1, top_ = -1e9;
  int layer_ = 0;
  std::string object_, idea_;
};

std::vector<Extrusion> replay(std::string_view text, Replay& r) {
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t nl = text.find('\n', at);
    if (nl == std::string_view::npos) nl = text.size();
    r.line(text.substr(at, nl - at));
    at = nl + 1;
  }
  return r.extrusions;
}

// "box:x0,y0,x1,y1": both ends of the extrusion within it (a file without labels).
bool in_box(const Extrusion& x, const std::string& spec) {
  double b[4] = {0, 0, 0, 0};
  const char* p = spec.c_str() + 4;
  for (double& v : b) {
    char* end = nullptr;
    v = std::strtod(p, &end);
    p = *end == ',' ? end + 1 : end;
  }
  return x.start[0] >= b[0] && x.start[0] <= b[2] && x.start[1] >= b[1] && x.start[1] <= b[3] && x.end[0] >= b[0] &&
         x.end[0] <= b[2] && x.end[1] >= b[1] && x.end[1] <= b[3];
}

bool left_out_object(const Extrusion& x, const std::vector<std::string>& left_out) {
  for (const std::string& l : left_out)
    if (l.rfind("box:", 0) == 0 && in_box(x, l)) return true;
  const std::string& object = x.object;
  if (object.empty()) return false;
  const std::size_t bar = object.find('|');
  const std::string name = object.substr(0, bar), id = object.substr(bar + 1);
  // By the label's number where it has one (copies share a name), else its name.
  for (const std::string& l : left_out)
    if (id.empty() ? l == name : l == id) return true;
  return false;
}

bool near(double a, double b) { return std::fabs(a - b) < 1e-6; }

std::string where(const Extrusion& x) {
  std::ostringstream s;
  s << "(" << x.start[0] << "," << x.start[1] << "," << x.start[2] << ")->(" << x.end[0] << "," << x.end[1] << "," << x.end[2]
    << ") E" << x.filament << " depth " << x.depth_before << (x.fw_before ? " fw-retracted" : "") << " [" << x.object << "]";
  return s.str();
}

}  // namespace object_check

using namespace object_check;

ObjectCheck check_objects_left_out(std::string_view input, std::string_view output, const std::vector<std::string>& left_out,
                                   int from_layer) {
  ObjectCheck result;
  Replay in, out;
  const std::vector<Extrusion> all = replay(input, in);
  const std::vector<Extrusion> got = replay(output, out);
  std::vector<Extrusion> want;
  for (const Extrusion& x : all) {
    if (left_out_object(x, left_out) && x.layer >= from_layer) {
      ++result.left_out;
    } else {
      want.push_back(x);
    }
  }
  auto fail = [&](std::string m) {
    result.ok = false;
    result.message = std::move(m);
    return result;
  };
  for (std::size_t i = 0; i < std::min(want.size(), got.size()); ++i) {
    const Extrusion &a = want[i], &b = got[i];
    bool same = near(a.filament, b.filament) && near(a.depth_before, b.depth_before) && a.fw_before == b.fw_before;
    for (int k = 0; k < 3; ++k) same = same && near(a.start[k], b.start[k]) && near(a.end[k], b.end[k]);
    if (!same) return fail("extrusion " + std::to_string(i) + ": input " + where(a) + ", output " + where(b));
    ++result.kept;
  }
  if (want.size() != got.size())
    return fail("the output has " + std::to_string(got.size()) + " extrusions, the input " + std::to_string(want.size()) +
                " outside the left-out objects");
  if (!near(in.depth, out.depth) || in.fw != out.fw)
    return fail("the end: retracted " + std::to_string(out.depth) + " mm, the input " + std::to_string(in.depth));
  for (int k = 0; k < 3; ++k)
    if (!near(in.pos[k], out.pos[k])) return fail("the end: the position differs from the input's on axis " + std::to_string(k));
  return result;
}

}  // namespace gctest
