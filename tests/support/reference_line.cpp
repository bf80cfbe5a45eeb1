// The line parser as it was before the single-pass rewrite, kept as the
// reference the new one is compared with (tests/unit/core/test_line.cpp and the
// fuzzer): the same fields for every input.
#include "reference_line.hpp"

#include "gcode/core/number.hpp"

namespace gctest {

using namespace gcode;

void ReferenceLine::add_word(const Word& w) {
  if (words.size() < Line::kMaxWords) {
    words.push_back(w);
  } else {
    malformed = true;
  }
}

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

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// Only "(...)" groups and blanks up to the end or a ';' comment. A group
// ends at the first ')', whatever it holds (';' and '(' included); an
// unclosed one runs to the end of the line.
bool is_paren_comment_line(const char* p, const char* end) {
  bool inside = false;
  for (; p != end; ++p) {
    if (inside) {
      inside = *p != ')';
    } else if (*p == '(') {
      inside = true;
    } else if (*p == ';') {
      return true;
    } else if (!is_space(*p)) {
      return false;
    }
  }
  return true;
}

// The first ';' from p on, outside "(...)" groups when `parens` (among a
// command's words) and anywhere when not (free text knows no parentheses);
// `end` when none.
const char* comment_start(const char* p, const char* end, bool parens) {
  bool inside = false;
  for (; p != end; ++p) {
    if (inside) {
      inside = *p != ')';
    } else if (*p == ';') {
      return p;
    } else if (parens && *p == '(') {
      inside = true;
    }
  }
  return end;
}

// Splits what follows p into code, the checksum "*nn" at the code's end
// and the ';' comment, into `line`; returns where the code ends.
const char* split_code(ReferenceLine& line, const char* p, const char* end, bool parens) {
  line.comment = {};
  line.comment_pos = std::string_view::npos;
  line.has_checksum = false;
  line.checksum = 0;
  const char* code_end = comment_start(p, end, parens);
  if (code_end != end) {
    line.comment = std::string_view(code_end, static_cast<std::size_t>(end - code_end));
    line.comment_pos = static_cast<std::size_t>(code_end - line.text.data());
  }
  const char* q = code_end;
  while (q != p && is_space(q[-1])) --q;
  const char* digits_end = q;
  while (q != p && is_digit(q[-1])) --q;
  if (q != p && q[-1] == '*' && q != digits_end) {
    double v = 0;
    if (parse_number(std::string_view(q, static_cast<std::size_t>(digits_end - q)), v) && v < 256) {
      line.has_checksum = true;
      line.checksum = static_cast<int>(v);
      code_end = q - 1;
    }
  }
  return code_end;
}

}  // namespace

ReferenceLine reference_parse(std::string_view text) {
  ReferenceLine line;
  line.text = text;
  const char* const begin = text.data();
  const char* p = begin;
  const char* end = p + text.size();

  while (p != end && is_space(*p)) ++p;
  if (p != end && *p == '(' && is_paren_comment_line(p, end)) {
    line.comment = std::string_view(p, static_cast<std::size_t>(end - p));
    line.comment_pos = static_cast<std::size_t>(p - begin);
    return line;
  }
  // A ';' comment ends the code (M117 messages cannot hold ';'), and a
  // checksum comes before it.
  const char* code_end = split_code(line, p, end, false);
  if (p == code_end) return line;

  // Optional line number.
  if ((*p == 'N' || *p == 'n') && p + 1 != code_end && is_digit(p[1])) {
    const char* q = p + 1;
    long long n = 0;
    // Capped as Line::parse caps it: twenty digits must not overflow.
    while (q != code_end && is_digit(*q)) {
      if (n < (1LL << 58)) n = n * 10 + (*q - '0');
      ++q;
    }
    line.has_line_number = true;
    line.line_number = n;
    p = q;
    while (p != code_end && is_space(*p)) ++p;
    if (p == code_end) return line;
  }

  const char* command_start = p;
  if (*p == '@') {
    // Host command: "@pause", "@TOOLCHANGE 1".
    ++p;
    while (p != code_end && !is_space(*p)) ++p;
    line.kind = CommandKind::Host;
    line.command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
    line.argument = trim(std::string_view(p, static_cast<std::size_t>(code_end - p)));
    return line;
  }
  if (is_alpha(*p) && p + 1 != code_end && (is_alpha(p[1]) || p[1] == '_')) {
    // Macro: a name of two or more letters ("PAUSE", "PRINT_START EXTRUDER=210").
    while (p != code_end && !is_space(*p)) ++p;
    line.kind = CommandKind::Extended;
    line.command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
    line.argument = trim(std::string_view(p, static_cast<std::size_t>(code_end - p)));
    return line;
  }
  if (!is_alpha(*p)) {
    line.malformed = true;
    return line;
  }

  // Standard command: a letter and a number ("G1", "M104", "T0", "G29.1").
  line.kind = CommandKind::Standard;
  line.letter = upper(*p);
  ++p;
  while (p != code_end && is_space(*p)) ++p;
  if (p == code_end || !is_digit(*p)) {
    line.malformed = true;  // "G" alone, "Gx"
    line.command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
    return line;
  }
  int n = 0;
  while (p != code_end && is_digit(*p)) {
    if (n < 100000) n = n * 10 + (*p - '0');
    ++p;
  }
  line.number = n;
  if (p != code_end && *p == '.' && p + 1 != code_end && is_digit(p[1])) {
    ++p;
    int s = 0;
    // Capped like the command number (and like Line::parse): a subcode of a
    // dozen digits is junk, and must not overflow.
    while (p != code_end && is_digit(*p)) {
      if (s < 100000) s = s * 10 + (*p - '0');
      ++p;
    }
    line.subcode = s;
  }
  line.command = std::string_view(command_start, static_cast<std::size_t>(p - command_start));
  if (takes_string_argument(line.letter, line.number)) {
    line.argument = trim(std::string_view(p, static_cast<std::size_t>(code_end - p)));
    return line;
  }

  // Words: among them a ';' inside "(...)" is the group's text.
  code_end = split_code(line, p, end, true);
  while (p != code_end) {
    char c = *p;
    if (is_space(c)) {
      ++p;
      continue;
    }
    if (c == '(') {
      // RepRap-style inline comment: skipped; the first one is kept as the comment.
      const char* close = p;
      while (close != code_end && *close != ')') ++close;
      if (close != code_end) ++close;
      if (line.comment.empty()) {
        line.comment = std::string_view(p, static_cast<std::size_t>(close - p));
        line.comment_pos = static_cast<std::size_t>(p - begin);
      }
      p = close;
      continue;
    }
    if (!is_alpha(c)) {
      line.malformed = true;
      ++p;
      continue;
    }
    Word w;
    w.letter = upper(c);
    ++p;
    const char* value_start = p;
    while (value_start != code_end && (*value_start == ' ' || *value_start == '\t')) ++value_start;
    if (value_start != code_end && starts_number(*value_start)) {
      bool ok = scan_number(value_start, code_end, w);
      p = value_start + w.raw.size();
      if (ok) {
        w.has_value = true;
      } else {
        line.malformed = true;  // "X-", "X1e309", "X1.2.3"
      }
    } else {
      w.raw = std::string_view(p, 0);  // a flag: empty, placed right after its letter
      if (p != code_end && is_alpha(*p)) line.malformed = true;  // "Xnan": a letter glued to letters is no flag word
    }
    line.add_word(w);
  }
  return line;
}


}  // namespace gctest

namespace gctest {

std::string compare_with_reference(const gcode::Line& line, const ReferenceLine& ref) {
  std::string diff;
  auto field = [&diff](const char* name, bool same) {
    if (!same) diff += std::string(diff.empty() ? "" : ", ") + name;
  };
  field("kind", line.kind == ref.kind);
  field("letter", line.letter == ref.letter);
  field("number", line.number == ref.number);
  field("subcode", line.subcode == ref.subcode);
  field("command", line.command == ref.command);
  field("argument", line.argument == ref.argument);
  field("comment", line.comment == ref.comment);
  field("comment_pos", line.comment_pos == ref.comment_pos);
  field("line number", line.has_line_number == ref.has_line_number && line.line_number == ref.line_number);
  field("checksum", line.has_checksum == ref.has_checksum && line.checksum == ref.checksum);
  field("malformed", line.malformed == ref.malformed);
  field("word count", line.word_count() == ref.words.size());
  for (std::size_t i = 0; i < line.word_count() && i < ref.words.size(); ++i) {
    const gcode::Word& a = line.word(i);
    const gcode::Word& b = ref.words[i];
    bool same = a.letter == b.letter && a.has_value == b.has_value && a.raw == b.raw &&
                (a.raw.empty() || a.raw.data() == b.raw.data());
    if (a.has_value && b.has_value) same = same && a.decimals == b.decimals && a.value() == b.value() && a.fixed() == b.fixed();
    field(("word " + std::to_string(i)).c_str(), same);
  }
  return diff;
}

}  // namespace gctest
