// The table of gc-send's control verbs (gcode/serial/control_verbs.hpp):
// each row complete, each verb read back by its own words, and what the
// journal keeps of a verb put back by a resume.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "gcode/serial/control/control_verbs.hpp"

using namespace gcode::serial;

TEST_CASE("control verbs: every row has a name, a help line and a handler, no name twice", "[serial][control]") {
  std::set<std::string_view> names;
  for (const ControlVerb& v : control_verbs()) {
    INFO(v.name);
    CHECK(!v.name.empty());
    CHECK(!v.help.empty());
    CHECK(v.handle != nullptr);
    CHECK(names.insert(v.name).second);
    for (char c : v.name) CHECK((c == ' ' || (c >= 'a' && c <= 'z')));
    // Kept by the journal: a field, its value and the way back, all three.
    bool kept = !v.journal_field.empty();
    CHECK((v.journal != nullptr) == kept);
    CHECK((v.restore != nullptr) == kept);
    CHECK(find_control_verb(v.name) == &v);
  }
}

TEST_CASE("control verbs: each is read by its own words, in any case, with its argument", "[serial][control]") {
  for (const ControlVerb& v : control_verbs()) {
    std::string line(v.name);
    for (char& c : line) c = static_cast<char>(c - ('a' <= c && c <= 'z' ? 'a' - 'A' : 0));
    if (!v.argument.empty()) line += " 2";
    INFO(line);
    ControlCommand c = parse_control_command(line);
    CHECK(c.verb == &v);
    CHECK(c.argument == (v.argument.empty() ? "" : "2"));
    if (v.argument.empty()) {
      CHECK(parse_control_command(std::string(v.name) + " 7").verb == nullptr);
    } else {
      CHECK(parse_control_command(v.name).verb == nullptr);
    }
  }
}

TEST_CASE("control verbs: the verb with the most matching words wins", "[serial][control]") {
  CHECK(parse_control_command("pause now").is("pause now"));
  CHECK(parse_control_command("pause  \t NOW").is("pause now"));
  ControlCommand later = parse_control_command("pause later");
  CHECK(later.verb == nullptr);
  CHECK(later.argument == "'pause' takes no argument: 'pause later'");
  CHECK(parse_control_command("pausenow").verb == nullptr);
}
