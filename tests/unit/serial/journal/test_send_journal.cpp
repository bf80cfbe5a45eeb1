// The journal while gc-send prints (gcode/serial/journal/send_journal.hpp):
// each numbered command a record with where its input line ends, the
// newest acknowledgement, and the end of the print, read back as written.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/core/machine_state.hpp"
#include "gcode/serial/journal/send_journal.hpp"
#include "gcode/serial/link/private_path.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("send journal: commands, offsets, acknowledgement and the end, read back", "[serial][send_journal]") {
  const std::string path = gctest::temp_dir() + "/send_journal/print.journal";
  make_private_folder(path);
  const gcode::MachineState state;
  const ResumeTrack track;
  {
    InputIdentity input;
    input.path = "/home/me/part.gcode";
    SendJournal journal(JournalOptions{.path = path}, input, "/dev/ttyACM0");
    journal.line_end(1, 10);
    journal.line_end(2, 25);
    journal.numbered(NumberedCommand{.n = 1, .source_line = 1, .layer = 0, .after = &state, .track = &track});
    journal.numbered(NumberedCommand{.n = 2, .source_line = 2, .layer = 1, .after = &state, .track = &track});
    journal.acknowledged(2);
    journal.flush(1.0);
    journal.finish(2.0);
  }
  const JournalContents back = read_journal(path);
  CHECK(back.header.get("port") == "/dev/ttyACM0");
  REQUIRE(back.entries.size() == 2);
  CHECK(back.entries[0].n == 1);
  CHECK(back.entries[0].point.get("off") == "10");
  CHECK(back.entries[1].point.get("off") == "25");
  CHECK(back.entries[1].point.get("layer") == "1");
  CHECK(back.acknowledged == 2);
  CHECK(back.finished);
}
