#include "gcode/core/line_edit.hpp"

#include "gcode/core/number.hpp"

namespace gcode {

LineEdit& LineEdit::set(char letter, std::string_view value) {
  for (Change& c : changes_)
    if (c.letter == letter) {
      c = Change{letter, false, std::string(value)};
      return *this;
    }
  changes_.push_back(Change{letter, false, std::string(value)});
  return *this;
}

LineEdit& LineEdit::set(char letter, Fixed value, int decimals) {
  char buffer[kMaxNumberChars];
  return set(letter, std::string_view(buffer, value.format(decimals, buffer)));
}

LineEdit& LineEdit::remove(char letter) {
  for (Change& c : changes_)
    if (c.letter == letter) {
      c = Change{letter, true, {}};
      return *this;
    }
  changes_.push_back(Change{letter, true, {}});
  return *this;
}

LineEdit& LineEdit::note(std::string_view text) {
  note_.assign(text);
  return *this;
}

std::string_view LineEdit::text() {
  const std::string_view src = line_.text;
  const char* base = src.data();
  auto offset = [base](const char* p) { return static_cast<std::size_t>(p - base); };
  std::string_view code = line_.code();
  const std::size_t code_end = code.empty() ? 0 : offset(code.data()) + code.size();
  std::vector<bool> done(changes_.size(), false);
  text_.clear();
  std::size_t copied = 0;  // src[0, copied) is in text_ already
  for (const Word& w : line_) {
    std::size_t i = 0;
    while (i < changes_.size() && changes_[i].letter != w.letter) ++i;
    if (i == changes_.size() || w.raw.data() == nullptr) continue;
    std::size_t value_begin = offset(w.raw.data()), value_end = value_begin + w.raw.size();
    if (changes_[i].remove) {
      // The letter, its value and the blanks before it go.
      std::size_t start = value_begin;
      while (start > 0 && src[start - 1] != w.letter && src[start - 1] != w.letter + ('a' - 'A')) --start;
      if (start > 0) --start;
      while (start > copied && (src[start - 1] == ' ' || src[start - 1] == '\t')) --start;
      text_.append(src.substr(copied, start - copied));
      copied = value_end;
    } else if (!done[i]) {
      text_.append(src.substr(copied, value_begin - copied));
      text_.append(changes_[i].value);
      copied = value_end;
    }
    done[i] = true;
  }
  text_.append(src.substr(copied, code_end > copied ? code_end - copied : 0));
  if (code_end > copied) copied = code_end;
  for (std::size_t i = 0; i < changes_.size(); ++i) {
    if (done[i] || changes_[i].remove) continue;
    text_.push_back(' ');
    text_.push_back(changes_[i].letter);
    text_.append(changes_[i].value);
  }
  text_.append(src.substr(copied));
  if (!note_.empty()) {
    text_.append(" ; ");
    text_.append(note_);
  }
  return text_;
}

}  // namespace gcode
