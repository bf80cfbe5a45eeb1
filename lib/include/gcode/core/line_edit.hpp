#pragma once
// Changes some words of a line and keeps the rest as it was: the command,
// the other words with their spacing, and the comment.
//
//   LineEdit edit(t.line);
//   edit.set('F', Fixed::from_int(5400), 0).note("gc-speedup x3");
//   out.replace(t, edit.text());     // "G1 X10 Y5 F5400 ; outer wall ; gc-speedup x3"
//
// A word that is there gets its new value in place; a new word goes after
// the last word, before the comment. Lines with a line number or checksum
// ("N12 G1 X1*34") are a sender's business: edit them and the checksum no
// longer fits, so tools leave them alone.
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/fixed.hpp"
#include "gcode/core/line.hpp"

namespace gcode {

class LineEdit {
 public:
  explicit LineEdit(const Line& line) : line_(line) {}

  // The value of the first `letter` word becomes `value` (text as written).
  LineEdit& set(char letter, std::string_view value);
  // The same with a number, written with at most `decimals` digits.
  LineEdit& set(char letter, Fixed value, int decimals);
  // Removes every `letter` word.
  LineEdit& remove(char letter);
  // Adds "; text" after the line's comment (or as its comment).
  LineEdit& note(std::string_view text);

  // The edited line (no ending); valid until the next call.
  std::string_view text();

 private:
  struct Change {
    char letter;
    bool remove;
    std::string value;
  };
  const Line& line_;
  std::vector<Change> changes_;
  std::string note_;
  std::string text_;
};

}  // namespace gcode
