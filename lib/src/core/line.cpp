#include "gcode/core/line.hpp"

#include <cstdint>
#include <cstring>
#include <new>

#include "gcode/core/number.hpp"
#include "gcode/core/text.hpp"

namespace gcode {

namespace {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
inline char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }
inline bool starts_number(char c) { return is_digit(c) || c == '-' || c == '+' || c == '.'; }

// Length of the number text starting at p: sign, digits, one point, and a
// lower-case C exponent ("1e309"); upper-case 'E' always starts a new word
// because packed lines such as "G1X5E2" are common and exponents are not.
std::size_t number_length(const char* p, const char* end) {
  const char* q = p;
  if (q != end && (*q == '-' || *q == '+')) ++q;
  while (q != end && (is_digit(*q) || *q == '.')) ++q;
  if (q != end && *q == 'e' && q != p) {
    const char* r = q + 1;
    if (r != end && (*r == '-' || *r == '+')) ++r;
    if (r != end && is_digit(*r)) {
      while (r != end && is_digit(*r)) ++r;
      q = r;
    }
  }
  return static_cast<std::size_t>(q - p);
}

// Scans the number text starting at p (the extent number_length gives) into
// `w`: its digits as an integer and its count of decimals, one pass and no
// floating point for the plain decimals slicers write. Anything else (an
// exponent, 19 or more digits) is checked with parse_number and marked not
// plain, so its value is read from the text when asked for.
// Returns false when the text is no finite number ("-", "1.2.3", "1e999").
bool scan_number(const char* p, const char* end, Word& w) {
  const char* q = p;
  bool negative = false;
  if (q != end && (*q == '-' || *q == '+')) {
    negative = *q == '-';
    ++q;
  }
  // Integer digits, then at most one point and the fraction digits.
  std::uint64_t mantissa = 0;
  const char* int_start = q;
  for (unsigned d; q != end && (d = static_cast<unsigned char>(*q) - unsigned{'0'}) <= 9; ++q)
    mantissa = mantissa * 10 + d;
  int digits = static_cast<int>(q - int_start);
  int points = 0, fraction_digits = 0;
  if (q != end && *q == '.') {
    points = 1;
    const char* frac_start = ++q;
    for (unsigned d; q != end && (d = static_cast<unsigned char>(*q) - unsigned{'0'}) <= 9; ++q)
      mantissa = mantissa * 10 + d;
    fraction_digits = static_cast<int>(q - frac_start);
    digits += fraction_digits;
    // A second point ("1.2.3"): the text runs on like number_length says.
    while (q != end && (*q == '.' || (*q >= '0' && *q <= '9'))) {
      points += *q == '.';
      ++q;
    }
  }
  w.decimals = static_cast<std::uint8_t>(fraction_digits > 255 ? 255 : fraction_digits);
  if (q != end && *q == 'e') {
    w.raw = std::string_view(p, number_length(p, end));
    w.plain = false;
    double v = 0;
    return parse_number(w.raw, v) && v - v == 0;
  }
  w.raw = std::string_view(p, static_cast<std::size_t>(q - p));
  if (digits == 0 || points > 1) return false;
  if (digits > 18) {
    w.plain = false;
    double v = 0;
    return parse_number(w.raw, v) && v - v == 0;
  }
  w.mantissa = negative ? -static_cast<std::int64_t>(mantissa) : static_cast<std::int64_t>(mantissa);
  return true;
}

}  // namespace

namespace {

// A view into a line's text moved to the same place in a copy of it.
inline std::string_view moved(std::string_view v, std::uintptr_t from, std::uintptr_t to) {
  if (v.data() == nullptr) return v;
  return std::string_view(reinterpret_cast<const char*>(reinterpret_cast<std::uintptr_t>(v.data()) - from + to), v.size());
}

}  // namespace

void Line::copy_onto(std::string_view new_text, Line& out) const {
  const auto from = reinterpret_cast<std::uintptr_t>(text.data());
  const auto to = reinterpret_cast<std::uintptr_t>(new_text.data());
  out.text = new_text;
  out.kind = kind;
  out.letter = letter;
  out.number = number;
  out.subcode = subcode;
  out.command = moved(command, from, to);
  out.argument = moved(argument, from, to);
  out.comment = moved(comment, from, to);
  out.comment_pos = comment_pos;
  out.has_line_number = has_line_number;
  out.line_number = line_number;
  out.has_checksum = has_checksum;
  out.checksum = checksum;
  out.malformed = malformed;
  out.count_ = count_;
  for (std::size_t i = 0; i < count_; ++i) {
    Word& w = *::new (&out.words_.at[i]) Word(words_.at[i]);
    w.raw = moved(w.raw, from, to);
  }
}

void Line::rebase(std::string_view new_text) {
  const auto from = reinterpret_cast<std::uintptr_t>(text.data());
  const auto to = reinterpret_cast<std::uintptr_t>(new_text.data());
  text = new_text;
  command = moved(command, from, to);
  argument = moved(argument, from, to);
  comment = moved(comment, from, to);
  for (std::size_t i = 0; i < count_; ++i) words_.at[i].raw = moved(words_.at[i].raw, from, to);
}

double Word::value_slow() const {
  double v = 0;
  parse_number(raw, v);
  return v;
}

Fixed Word::fixed_slow() const { return Fixed::from_double(value_slow()); }

bool takes_string_argument(char letter, int number) {
  if (letter != 'M') return false;
  switch (number) {
    case 23: case 28: case 30: case 32: case 33: case 117: case 118: case 928:
      return true;
    default:
      return false;
  }
}

std::string_view Line::comment_text() const {
  std::string_view c = comment;
  if (c.empty()) return c;
  if (c.front() == ';') {
    c.remove_prefix(1);
  } else if (c.front() == '(') {
    c.remove_prefix(1);
    if (!c.empty() && c.back() == ')') c.remove_suffix(1);
  }
  return trim(c);
}

std::string_view Line::code() const {
  std::string_view c = comment_pos == std::string_view::npos ? text : text.substr(0, comment_pos);
  while (!c.empty() && is_space(c.back())) c.remove_suffix(1);
  return c;
}

namespace {

// "*nn" at p followed only by blanks up to the end or (`comment_may_follow`)
// a ';' comment: the checksum of a numbered line (its value, else -1).
int checksum_at(const char* p, const char* end, bool comment_may_follow = true) {
  const char* q = p + 1;
  int value = 0;
  const char* digits = q;
  while (q != end && is_digit(*q)) {
    if (value < 1000) value = value * 10 + (*q - '0');
    ++q;
  }
  if (q == digits || value > 255) return -1;
  while (q != end && is_space(*q)) ++q;
  return q == end || (comment_may_follow && *q == ';') ? value : -1;
}

bool read_checksum(const char* p, const char* end, Line& line) {
  int value = checksum_at(p, end);
  if (value < 0) return false;
  line.has_checksum = true;
  line.checksum = value;
  return true;
}

// "(...)" comments and blanks up to the end or a ';' comment: a comment line
// (RepRap/LinuxCNC style; Marlin reads them with PAREN_COMMENTS). Read as
// those firmwares read them: the first ')' closes one, whatever is inside
// ("(a;b)", "(width (3.2mm^3/s)": a ';' or '(' there is its text), and an
// unclosed one runs to the end of the line. So "(a (b) c)" is not one.
bool only_paren_comments(const char* p, const char* end) {
  while (p != end && *p == '(') {
    const void* close = std::memchr(p, ')', static_cast<std::size_t>(end - p));
    if (close == nullptr) return true;
    p = static_cast<const char*>(close) + 1;
    while (p != end && is_space(*p)) ++p;
  }
  return p == end || *p == ';';
}

}  // namespace

// Where the code of a line ends: before its ';' comment and its "*nn"
// checksum. The free-text commands (host commands, macros, M117 ...) need it
// up front; ordinary commands find both on their way through the words.
const char* Line::find_code_end(const char* p, const char* end) {
  const char* code_end = end;
  if (const void* semi = std::memchr(p, ';', static_cast<std::size_t>(end - p)); semi != nullptr) {
    code_end = static_cast<const char*>(semi);
    comment = std::string_view(code_end, static_cast<std::size_t>(end - code_end));
    comment_pos = static_cast<std::size_t>(code_end - text.data());
  }
  const char* q = code_end;
  while (q != p && is_space(q[-1])) --q;
  const char* digits_end = q;
  while (q != p && is_digit(q[-1])) --q;
  if (q != p && q[-1] == '*' && q != digits_end && read_checksum(q - 1, code_end, *this)) code_end = q - 1;
  return code_end;
}

// The steps every command line takes are forced inline: parse() is the
// hottest function of a full pass, and a call for each would cost it.

// "N123" at p: the line number; then p is past it and its blanks. True when
// the line ends there (nothing, a comment or a checksum follows).
bool Line::parse_line_number(const char*& p, const char* end) {
  const char* q = p + 1;
  long long n = 0;
  while (q != end && is_digit(*q)) {
    if (n < (1LL << 58)) n = n * 10 + (*q - '0');
    ++q;
  }
  has_line_number = true;
  line_number = n;
  p = q;
  while (p != end && is_space(*p)) ++p;
  if (p == end) return true;
  if (*p == ';' || (*p == '*' && read_checksum(p, end, *this))) {
    find_code_end(p, end);
    return true;
  }
  return false;
}

// Host command ("@pause", "@TOOLCHANGE 1") or macro of two or more letters
// ("PAUSE", "PRINT_START EXTRUDER=210"): a name and free text.
void Line::parse_free_text(const char* p, const char* end) {
  const char* const command_start = p;
  const char* code_end = find_code_end(p, end);
  kind = *p == '@' ? CommandKind::Host : CommandKind::Extended;
  while (p != code_end && !is_space(*p)) ++p;
  command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
  argument = trim(std::string_view(p, static_cast<std::size_t>(code_end - p)));
}

// A standard command's letter and number ("G1", "M104", "T0", "G29.1") at p;
// then p is past them. False for a letter without a number ("G" alone,
// "Gx"): a malformed line, complete.
[[gnu::always_inline]] inline bool Line::parse_command(const char*& p, const char* end) {
  const char* const command_start = p;
  kind = CommandKind::Standard;
  letter = upper(*p);
  ++p;
  while (p != end && is_space(*p)) ++p;
  if (p == end || !is_digit(*p)) {
    const char* code_end = find_code_end(command_start, end);
    if (p > code_end) p = code_end;
    malformed = true;
    command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
    return false;
  }
  int n = 0;
  while (p != end && is_digit(*p)) {
    if (n < 100000) n = n * 10 + (*p - '0');
    ++p;
  }
  number = n;
  if (p + 1 < end && *p == '.' && is_digit(p[1])) {
    ++p;
    int sub = 0;
    while (p != end && is_digit(*p)) {
      if (sub < 100000) sub = sub * 10 + (*p - '0');
      ++p;
    }
    subcode = sub;
  }
  command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
  return true;
}

// One word at p (its letter, then a number or nothing: a flag); returns where
// the scan goes on. Past kMaxWords words the rest go to `spare` and the line
// is malformed.
[[gnu::always_inline]] inline const char* Line::parse_word(const char* p, const char* end, Word& spare) {
  Word* w = count_ < kMaxWords ? ::new (&words_.at[count_++]) Word() : &spare;
  if (w == &spare) malformed = true;
  w->letter = upper(*p);
  ++p;
  const char* value_start = p;
  while (value_start != end && (*value_start == ' ' || *value_start == '\t')) ++value_start;
  if (value_start != end && starts_number(*value_start)) {
    w->has_value = scan_number(value_start, end, *w);
    malformed = malformed || !w->has_value;  // "X-", "X1e309", "X1.2.3"
    return value_start + w->raw.size();
  }
  w->raw = std::string_view(p, 0);  // a flag: empty, placed right after its letter
  if (p != end && is_alpha(*p)) malformed = true;  // "Xnan": a letter glued to letters is no flag word
  return p;
}

// A RepRap-style inline comment "(...)" at p: skipped; the first one is kept
// as the comment. It ends at the first ')' (a ';' inside is its text, as in
// a whole line of them, see only_paren_comments); an unclosed one at the
// line's checksum or its end. Returns where the scan goes on.
const char* Line::skip_paren_comment(const char* p, const char* end) {
  const char* close = p;
  while (close != end && *close != ')' && !(*close == '*' && checksum_at(close, end, false) >= 0)) ++close;
  if (close != end && *close == ')') ++close;
  if (comment.empty()) {
    comment = std::string_view(p, static_cast<std::size_t>(close - p));
    comment_pos = static_cast<std::size_t>(p - text.data());
  }
  return close;
}

// The words after the command, up to a ';' comment or a checksum.
[[gnu::always_inline]] inline void Line::parse_words(const char* p, const char* end) {
  Word spare;
  while (p != end) {
    const char c = *p;
    if (c == ' ') {
      ++p;
      continue;
    }
    if (c == ';') {
      comment = std::string_view(p, static_cast<std::size_t>(end - p));
      comment_pos = static_cast<std::size_t>(p - text.data());
      return;
    }
    if (is_alpha(c)) {
      p = parse_word(p, end, spare);
      continue;
    }
    if (is_space(c)) {
      ++p;
      continue;
    }
    if (c == '(') {
      p = skip_paren_comment(p, end);
      continue;
    }
    if (c == '*' && read_checksum(p, end, *this)) {
      if (const void* semi = std::memchr(p, ';', static_cast<std::size_t>(end - p)); semi != nullptr) {
        const char* at = static_cast<const char*>(semi);
        comment = std::string_view(at, static_cast<std::size_t>(end - at));
        comment_pos = static_cast<std::size_t>(at - text.data());
      }
      return;
    }
    malformed = true;
    ++p;
  }
}

namespace {

// A plain decimal at p ("-12.5", ".8", "3"), of at most 18 digits and ended
// by a blank, a ';' or the line's end, into `w` exactly as scan_number reads
// it; else nullptr (anything else: the full parse decides).
[[gnu::always_inline]] inline const char* scan_plain(const char* p, const char* end, Word& w) {
  const char* q = p;
  const bool negative = q != end && *q == '-';
  q += negative;
  std::uint64_t mantissa = 0;
  const char* const int_start = q;
  for (unsigned d; q != end && (d = static_cast<unsigned char>(*q) - unsigned{'0'}) <= 9; ++q)
    mantissa = mantissa * 10 + d;
  std::ptrdiff_t digits = q - int_start, fraction = 0;
  if (q != end && *q == '.') {
    const char* const fraction_start = ++q;
    for (unsigned d; q != end && (d = static_cast<unsigned char>(*q) - unsigned{'0'}) <= 9; ++q)
      mantissa = mantissa * 10 + d;
    fraction = q - fraction_start;
    digits += fraction;
  }
  if (digits == 0 || digits > 18 || (q != end && *q != ' ' && *q != ';')) return nullptr;
  w.has_value = true;
  w.plain = true;
  w.decimals = static_cast<std::uint8_t>(fraction);
  w.mantissa = negative ? -static_cast<std::int64_t>(mantissa) : static_cast<std::int64_t>(mantissa);
  w.raw = std::string_view(p, static_cast<std::size_t>(q - p));
  return q;
}

}  // namespace

// The lines that make up most of a file, "G1 X10.5 Y3 E.12" with upper-case
// letters, single blanks and plain numbers, read in one tight loop (the
// general scan cost twice as many instructions a line: callgrind). p is at
// "G0".."G3" followed by a blank or the end. False, with nothing kept, for
// anything else on the line: the general scan then reads it from the start.
bool Line::parse_move_fast(const char* p, const char* end) {
  const char* const command_start = p;
  p += 2;
  std::size_t n = 0;
  for (;;) {
    while (p != end && *p == ' ') ++p;
    if (p == end) break;
    const char c = *p;
    if (c == ';') {
      comment = std::string_view(p, static_cast<std::size_t>(end - p));
      comment_pos = static_cast<std::size_t>(p - text.data());
      break;
    }
    if (c < 'A' || c > 'Z' || n == kMaxWords) return false;
    Word& w = words_.at[n];
    const char* next = scan_plain(p + 1, end, w);
    if (next == nullptr) return false;
    w.letter = c;
    ++n;
    p = next;
  }
  count_ = n;
  kind = CommandKind::Standard;
  letter = 'G';
  number = command_start[1] - '0';
  command = std::string_view(command_start, 2);
  return true;
}

// One forward pass for what slicers write ("G1 X10.5 Y3 E0.12 ; c"): the
// comment, a checksum and the words are found as the scan reaches them.
Line Line::parse(std::string_view text) {
  Line line;
  line.text = text;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p != end && is_space(*p)) ++p;
  if (p == end) return line;
  if (*p == ';' || (*p == '(' && only_paren_comments(p, end))) {
    line.comment = std::string_view(p, static_cast<std::size_t>(end - p));
    line.comment_pos = static_cast<std::size_t>(p - text.data());
    return line;
  }
  if (*p == 'G' && end - p >= 2 && p[1] >= '0' && p[1] <= '3' && (end - p == 2 || p[2] == ' ') &&
      line.parse_move_fast(p, end))
    return line;
  // Optional line number ("N123 G1 ...").
  if ((*p == 'N' || *p == 'n') && p + 1 != end && is_digit(p[1]) && line.parse_line_number(p, end)) return line;
  if (*p == '@' || (is_alpha(*p) && p + 1 != end && (is_alpha(p[1]) || p[1] == '_'))) {
    line.parse_free_text(p, end);
    return line;
  }
  if (!is_alpha(*p)) {
    const char* code_end = line.find_code_end(p, end);
    line.malformed = p != code_end;
    return line;
  }
  if (!line.parse_command(p, end)) return line;
  if (takes_string_argument(line.letter, line.number)) {
    const char* code_end = line.find_code_end(p, end);
    line.argument = trim(std::string_view(p, static_cast<std::size_t>(code_end - p)));
    return line;
  }
  line.parse_words(p, end);
  return line;
}

}  // namespace gcode
