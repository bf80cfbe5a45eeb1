// One journal record as a line that checks itself
// (gcode/serial/journal/journal_record.hpp): written and read back the
// same, a value with a blank kept one field, a flipped byte caught.
#include <catch2/catch.hpp>

#include <optional>
#include <string>

#include "gcode/serial/journal/journal_record.hpp"

using namespace gcode::serial;

TEST_CASE("journal record: encoded and decoded the same, a blank escaped", "[serial][journal_record]") {
  JournalRecord record;
  record.type = 'D';
  record.fields.set("n", "1043");
  record.fields.set("input", "/home/me/my part.gcode");
  const std::string line = encode_journal_record(record);
  REQUIRE(line.back() == '\n');
  CHECK(line.find("my part") == std::string::npos);  // the blank is escaped
  RecordProblem problem = RecordProblem::Malformed;
  std::optional<JournalRecord> back = decode_journal_record(std::string_view(line).substr(0, line.size() - 1), &problem);
  REQUIRE(back);
  CHECK(problem == RecordProblem::None);
  CHECK(back->type == 'D');
  CHECK(back->fields == record.fields);
  CHECK(back->fields.count("n") == 1043);
}

TEST_CASE("journal record: a flipped byte fails the check", "[serial][journal_record]") {
  JournalRecord record;
  record.type = 'A';
  record.fields.set("n", "12");
  std::string line = encode_journal_record(record);
  line.pop_back();
  line[line.find("12")] = '7';
  RecordProblem problem = RecordProblem::None;
  CHECK_FALSE(decode_journal_record(line, &problem));
  CHECK(problem != RecordProblem::None);
}

TEST_CASE("journal record: fields keep their order, changes against a snapshot", "[serial][journal_record]") {
  JournalFields before;
  before.set("x", "1");
  before.set("y", "2");
  JournalFields after = before;
  after.set("y", "3");
  after.set("z", "4");
  JournalFields delta = after.changed_since(before);
  REQUIRE(delta.items().size() == 2);
  CHECK(delta.items()[0].first == "y");
  CHECK(delta.get("z") == "4");
  CHECK(delta.count("x") == 0);  // missing: 0
  before.update(delta);
  CHECK(before == after);
  CHECK(after.erase("z"));
  CHECK_FALSE(after.erase("z"));
  JournalFields odd;
  odd.set("n", "twelve");
  CHECK(odd.count("n") == 0);  // not a number: 0, no throw
}
