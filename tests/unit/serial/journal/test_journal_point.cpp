// A machine state as journal fields and back (gcode/serial/journal/journal_point.hpp):
// on every line of every fixture the state read back is the same machine,
// filament counter included, and a journal of a whole print rebuilds the
// state after every command from its deltas.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/core/line.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/journal/journal_point.hpp"
#include "test_support.hpp"

using namespace gcode;
using namespace gcode::serial;

namespace {

Line parsed(const std::string& raw) {
  std::string_view text = raw;
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
  return Line::parse(text);
}

MachineState read_back(const JournalFields& f) {
  MachineState s;
  std::string problem;
  REQUIRE(read_machine_fields(f, s, problem));
  CHECK(problem.empty());
  return s;
}

}  // namespace

TEST_CASE("journal point: every state of every fixture reads back as the same machine", "[serial][journal]") {
  for (const std::string& name : gctest::fixture_names()) {
    INFO(name);
    std::string text = gctest::read_file(gctest::fixture_path(name));
    MachineState state = gctest::initial_state(text);
    std::size_t checked = 0;
    // Written command after command as the journal writes them (the
    // settings only where they changed): the same fields as written whole.
    JournalFields running;
    MachineState before = state;
    write_machine_fields(state, running);
    for (const std::string& raw : gctest::split_lines(text)) {
      state.apply(parsed(raw));
      JournalFields f;
      write_machine_fields(state, f);
      MachineState back = read_back(f);
      if (!same_machine(back, state) || back.filament_total != state.filament_total) {
        FAIL_CHECK("differs after: " << raw);
        break;
      }
      write_machine_fields(state, running, &before);
      before = state;
      if (running != f) {
        FAIL_CHECK("written after the state before, differs after: " << raw);
        break;
      }
      ++checked;
    }
    CHECK(checked > 100);
  }
}

TEST_CASE("journal point: a whole print's journal rebuilds the state after every command", "[serial][journal]") {
  std::string text = gctest::read_file(gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode"));
  std::string path = gctest::temp_dir() + "/cube.journal";
  std::vector<MachineState> states;
  MachineState state = gctest::initial_state(text);
  {
    JournalOptions options{path};
    options.compact_bytes = std::size_t{64} << 20;  // all of it, to compare every command
    JournalWriter w(options, {});
    std::uint64_t n = 0;
    for (const std::string& raw : gctest::split_lines(text)) {
      Line line = parsed(raw);
      if (line.kind == CommandKind::None) continue;
      state.apply(line);
      JournalFields f;
      write_machine_fields(state, f);
      w.sent(++n, f);
      states.push_back(state);
      w.flush(static_cast<double>(n) * 0.01);
    }
    // A delta per command, not a snapshot: a G1 changes two or three fields.
    CHECK(w.bytes_written() < states.size() * 70);
  }
  JournalContents c = read_journal(path);
  REQUIRE(c.entries.size() == states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    MachineState back = read_back(c.entries[i].point);
    if (!same_machine(back, states[i])) {
      FAIL("command " << i + 1 << " differs");
    }
  }
}

TEST_CASE("journal point: a missing or unreadable field is named", "[serial][journal]") {
  MachineState s;
  JournalFields f;
  write_machine_fields(s, f);
  std::string problem;
  JournalFields missing = f;
  missing.erase("z");
  CHECK_FALSE(read_machine_fields(missing, s, problem));
  CHECK(problem == "field z (missing)");
  JournalFields bad = f;
  bad.set("f", "fast");
  CHECK_FALSE(read_machine_fields(bad, s, problem));
  CHECK(problem == "field f (fast)");
  bad = f;
  bad.set("x", "1.0000000001");  // more decimals than an exact position holds
  CHECK_FALSE(read_machine_fields(bad, s, problem));
  CHECK(problem.find("field x") == 0);
}
