#pragma once
// One record of gc-send's journal as one line of text that checks itself:
//
//   D n=1043 line=5120 off=183304 x=101.25 y=87.4 e=312.50021 #5a0c33e1
//
// a type letter, `key=value` fields, and the XXH32 of everything before the
// '#' in hex. A record cut short by a crash (no newline, or a check that
// fails on the last line) is recognised as such; so is a flipped byte in
// the middle. Values are escaped (%XX) where they hold a blank, '=', '#',
// '%' or a control byte, so a path with spaces stays one field.
#include <optional>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gcode::serial {

// A small ordered set of fields: records have a dozen or so, so a vector
// beats a map, and the order of first appearance is the order written.
// A point is set field by field in the same order command after command:
// each lookup tries the place after the last one first.
class JournalFields {
 public:
  // (A value copied into the field's own string: no allocation once it
  // has held one as long.)
  void set(std::string_view key, std::string_view value);
  const std::string* find(std::string_view key) const;
  std::string get(std::string_view key, std::string_view otherwise = {}) const;
  // A field that holds a whole number >= 0; 0 when it is missing or not one
  // (a damaged record must not throw out of a reader).
  std::uint64_t count(std::string_view key) const;
  bool erase(std::string_view key);
  // The fields of `other` taken over (a delta applied to a snapshot).
  void update(const JournalFields& other);
  // The fields of this that `before` lacks or holds at another value.
  JournalFields changed_since(const JournalFields& before) const;

  const std::vector<std::pair<std::string, std::string>>& items() const { return items_; }
  bool empty() const { return items_.empty(); }
  friend bool operator==(const JournalFields& a, const JournalFields& b) { return a.items_ == b.items_; }

 private:
  std::size_t index_of(std::string_view key, std::size_t hint) const;

  std::vector<std::pair<std::string, std::string>> items_;
  std::size_t next_ = 0;  // where the next set() looks first
};

struct JournalRecord {
  char type = 0;  // H header, S snapshot, D delta, A acknowledged, F finished
  JournalFields fields;
};

// The line for `record`, newline included.
std::string encode_journal_record(const JournalRecord& record);

enum class RecordProblem { None, Incomplete, BadCheck, Malformed };

// Reads one line (without its newline); `problem` says why it is not a record.
std::optional<JournalRecord> decode_journal_record(std::string_view line, RecordProblem* problem = nullptr);

}  // namespace gcode::serial
