#pragma once
// The previous line parser, kept as a reference for differential tests of
// gcode::Line::parse (see reference_line.cpp).
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/line.hpp"

namespace gctest {

struct ReferenceLine {
  std::string_view text;
  gcode::CommandKind kind = gcode::CommandKind::None;
  char letter = 0;
  int number = -1;
  int subcode = -1;
  std::string_view command;
  std::string_view argument;
  std::string_view comment;
  std::size_t comment_pos = std::string_view::npos;
  bool has_line_number = false;
  long long line_number = 0;
  bool has_checksum = false;
  int checksum = 0;
  bool malformed = false;
  std::vector<gcode::Word> words;
  void add_word(const gcode::Word& w);
};

ReferenceLine reference_parse(std::string_view text);
// Empty when `line` has the same fields as the reference; else what differs.
std::string compare_with_reference(const gcode::Line& line, const ReferenceLine& ref);

}  // namespace gctest
