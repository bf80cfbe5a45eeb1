// What the sender tells the journal of a numbered command
// (gcode/serial/protocol/numbered_command.hpp): a line of gc-send's own has
// no input line and keeps the input position of the one before; the closing
// M400 is marked.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/journal/send_journal.hpp"
#include "gcode/serial/link/private_path.hpp"
#include "gcode/serial/protocol/numbered_command.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("numbered command: an own line keeps the input line, closing marks the end", "[serial][numbered_command]") {
  NumberedCommand plain;
  CHECK(plain.source_line == 0);  // by default a line of gc-send's own
  CHECK_FALSE(plain.closing);
  CHECK_FALSE(plain.drains);
  const std::string path = gctest::temp_dir() + "/numbered_command/print.journal";
  make_private_folder(path);
  const gcode::MachineState state;
  const ResumeTrack track;
  {
    SendJournal journal(JournalOptions{.path = path}, InputIdentity{}, "virtual");
    journal.line_end(7, 70);
    journal.numbered(NumberedCommand{.n = 1, .source_line = 7, .layer = 2, .after = &state, .track = &track});
    journal.numbered(NumberedCommand{.n = 2, .after = &state, .track = &track});  // own: a pause block's line
    journal.numbered(NumberedCommand{.n = 3, .source_line = 0, .after = &state, .track = &track, .closing = true});
    journal.flush(1.0);
  }
  const JournalContents back = read_journal(path);
  REQUIRE(back.entries.size() == 3);
  CHECK(back.entries[0].point.get("own") == "0");
  CHECK(back.entries[1].point.get("own") == "1");
  CHECK(back.entries[1].point.get("line") == "7");
  CHECK(back.entries[1].point.get("off") == "70");
  CHECK(back.entries[1].point.get("end") == "0");
  CHECK(back.entries[2].point.get("end") == "1");
}
