#pragma once
// Builds the text of a changed or inserted line: "G1 X10.5 Y3 E0.12345 ; c".
// Numbers are written with number.hpp's format_number; the buffer is reused,
// so building a line allocates nothing once warmed up.
#include <string>
#include <string_view>

#include "gcode/core/fixed.hpp"
#include "gcode/core/number.hpp"

namespace gcode {

class LineBuilder {
 public:
  LineBuilder() { text_.reserve(256); }
  LineBuilder& start(std::string_view command) {
    text_.assign(command);
    return *this;
  }
  LineBuilder& word(char letter, double value, int decimals) {
    char buffer[kMaxNumberChars];
    text_.push_back(' ');
    text_.push_back(letter);
    text_.append(buffer, format_number(value, decimals, buffer));
    return *this;
  }
  // An exact decimal, written with all the digits it has (at most nine):
  // a position or E coordinate the file is at, written back exactly.
  LineBuilder& fixed(char letter, Fixed value, int decimals = Fixed::kDecimals) {
    char buffer[kMaxNumberChars];
    text_.push_back(' ');
    text_.push_back(letter);
    text_.append(buffer, value.format(decimals, buffer));
    return *this;
  }
  // A word whose value is copied as written (keeps the input's exact text).
  LineBuilder& raw_word(char letter, std::string_view raw) {
    text_.push_back(' ');
    text_.push_back(letter);
    text_.append(raw);
    return *this;
  }
  LineBuilder& text(std::string_view more) {
    text_.append(more);
    return *this;
  }
  // Appends a comment; `comment` includes its ';' or '('.
  LineBuilder& comment(std::string_view comment) {
    if (!comment.empty()) {
      text_.push_back(' ');
      text_.append(comment);
    }
    return *this;
  }
  std::string_view view() const { return text_; }
  const std::string& str() const { return text_; }

 private:
  std::string text_;
};

// The decimals to write per letter: at least the usual (X/Y/Z 3, E 5, F 0)
// and at least what the input itself used, so nothing written is coarser
// than what the slicer wrote.
class Precision {
 public:
  Precision();
  void observe_word(char letter, std::string_view raw) { observe(letter, decimals_of(raw)); }
  // For parsed words, which know their decimals already (no second scan).
  void observe(char letter, int decimals) {
    int& slot = decimals_[index(letter)];
    if (decimals > slot) slot = decimals > 9 ? 9 : decimals;
  }
  int of(char letter) const { return decimals_[index(letter)]; }

 private:
  static std::size_t index(char letter) {
    return (letter >= 'A' && letter <= 'Z') ? static_cast<std::size_t>(letter - 'A') : 26;
  }
  int decimals_[27];
};

}  // namespace gcode
