#pragma once
// A parsed view of one G-code line.
//
// Parsing never fails: a line that does not follow the grammar is still a
// Line, flagged `malformed`, and tools pass it through untouched. Accepts what
// Marlin accepts: lower case, packed words ("G1X10Y5E.5"), a leading '+', a
// missing leading zero, spaces between a letter and its number, an "N123"
// line number and a "*71" checksum, ';' and '(...)' comments.
//
// Parenthesis comments are read as the firmwares that have them read them
// (Marlin with PAREN_COMMENTS, RepRapFirmware in CNC mode, LinuxCNC): the
// first ')' closes one and everything before it is its text, a ';' or a
// '(' included; an unclosed one runs to the end of the line (to a
// checksum among the words). So "(a;b)" and "(width (3.26mm^3/s)" are
// comment lines, and "G1 X1 (a;b) Y2" moves X and Y. Free text (M117
// messages, host commands, macros) knows no parentheses: a ';' ends it.
#include <array>
#include <cstdint>
#include <string_view>

#include "gcode/core/fixed.hpp"

namespace gcode {

namespace detail {
inline constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
inline constexpr std::int64_t kExactDouble = std::int64_t{1} << 53;
}  // namespace detail

// One letter and its number. The number is kept as written: its digits as an
// integer and its count of decimals, so reading it needs no floating point
// and its exact decimal value (fixed()) is at hand for arithmetic that must
// not drift. value() gives the double for geometry.
struct Word {
  char letter = 0;            // always upper case
  bool has_value = false;     // false for "G28 X" style flags
  bool plain = true;          // a plain decimal of at most 18 digits: mantissa holds it
  std::uint8_t decimals = 0;  // digits after the point as written ("-.80" -> 2)
  std::int64_t mantissa = 0;  // the digits, signed: "-.80" -> -80 (with decimals 2)
  std::string_view raw;       // the value as written, e.g. "-.8"; a flag's is empty, placed after its letter

  // In the units written (no inch conversion); bit for bit what parsing the
  // text gives.
  [[gnu::always_inline]] double value() const {
    if (plain && mantissa < detail::kExactDouble && mantissa > -detail::kExactDouble)
      return static_cast<double>(mantissa) / detail::kPow10[decimals];
    return value_slow();
  }
  // The exact decimal (rounded only beyond nine decimals).
  [[gnu::always_inline]] Fixed fixed() const { return plain ? Fixed::from_decimal(mantissa, decimals) : fixed_slow(); }

 private:
  double value_slow() const;
  Fixed fixed_slow() const;
};

enum class CommandKind : std::uint8_t {
  None,      // blank or comment-only line
  Standard,  // letter + number: G1, M104, T0, G29.1
  Host,      // "@pause": commands for the host, never sent to firmware
  Extended,  // Klipper/RRF style macros: PRINT_START, SET_PRINT_STATS_INFO ...
};

class Line {
 public:
  static constexpr std::size_t kMaxWords = 24;

  // Parses `text` (a line without its ending). The Line views into `text`.
  static Line parse(std::string_view text);

  std::string_view text;     // the whole line, as read
  CommandKind kind = CommandKind::None;
  char letter = 0;           // 'G', 'M', 'T' ... for Standard commands
  int number = -1;           // 1 for G1
  int subcode = -1;          // 1 for G29.1
  std::string_view command;  // "G1", "@pause", "PRINT_START" as written
  std::string_view argument; // free text of M117/M118/M23/..., host and macro arguments
  std::string_view comment;  // ";..." or "(...)" including the marker; empty if none
  std::size_t comment_pos = std::string_view::npos;  // offset of the comment in text
  bool has_line_number = false;
  long long line_number = 0;
  bool has_checksum = false;
  int checksum = 0;
  bool malformed = false;    // stray bytes, a number that does not parse, too many words

  std::size_t word_count() const { return count_; }
  const Word& word(std::size_t i) const { return words_.at[i]; }
  const Word* begin() const { return words_.at; }
  const Word* end() const { return words_.at + count_; }

  // The word with this (upper-case) letter, or nullptr.
  const Word* find(char upper) const {
    for (std::size_t i = 0; i < count_; ++i)
      if (words_.at[i].letter == upper) return &words_.at[i];
    return nullptr;
  }
  bool has(char upper) const { return find(upper) != nullptr; }
  // The value of a word that has one, else `fallback`.
  double value_or(char upper, double fallback) const {
    const Word* w = find(upper);
    return (w != nullptr && w->has_value) ? w->value() : fallback;
  }

  bool is(char l, int n) const { return kind == CommandKind::Standard && letter == l && number == n; }
  bool is_g(int n) const { return is('G', n); }
  bool is_m(int n) const { return is('M', n); }
  bool is_move() const { return kind == CommandKind::Standard && letter == 'G' && number >= 0 && number <= 3 && subcode < 0; }
  bool is_blank() const { return kind == CommandKind::None && comment.empty(); }
  // Copies this line into `out` with every view moved onto `text`: the same
  // bytes at another place (a line kept for later in another buffer). Only
  // the words in use are copied. Addresses are compared as integers, so this
  // line's own text may be gone by now.
  void copy_onto(std::string_view text, Line& out) const;
  // The same in place: this line's views moved onto `text`, a copy of its text.
  void rebase(std::string_view text);

  // The text of the comment without its marker and surrounding spaces.
  std::string_view comment_text() const;
  // The code part: the text before the comment, trailing blanks removed.
  std::string_view code() const;

 private:
  const char* find_code_end(const char* p, const char* end);
  // The steps of parse(), in the order a line is read (line.cpp).
  bool parse_move_fast(const char* p, const char* end);
  bool parse_line_number(const char*& p, const char* end);
  void parse_free_text(const char* p, const char* end);
  bool parse_command(const char*& p, const char* end);
  void parse_words(const char* p, const char* end);
  const char* parse_word(const char* p, const char* end, Word& spare);
  const char* skip_paren_comment(const char* p, const char* end);

  // Left uninitialised: only the first count_ words are ever read, and
  // clearing all of them for every line was a quarter of Line::parse.
  union Words {
    Words() {}
    Word at[kMaxWords];
  };
  Words words_;
  std::size_t count_ = 0;
};

// Commands whose parameters are free text (a message or a file name), so
// their argument is never split into words: M117 "Printing 1.5mm" is no X word.
bool takes_string_argument(char letter, int number);

}  // namespace gcode
