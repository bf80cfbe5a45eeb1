// The journal's header (gcode/serial/journal/journal_header.hpp): the same file
// passes; another path, size or time, or a file for a stream, is named.
#include <catch2/catch.hpp>

#include "gcode/serial/journal/journal_header.hpp"

using namespace gcode::serial;

TEST_CASE("journal header: the same input passes, any change is named", "[serial][journal]") {
  InputIdentity file{"/prints/part.gcode", true, 1000, 1700000000123456789};
  JournalFields h = journal_header(file, "/dev/ttyACM0");
  CHECK(h.get("port") == "/dev/ttyACM0");
  CHECK(input_mismatch(h, file).empty());

  InputIdentity other = file;
  other.path = "/prints/other.gcode";
  CHECK(input_mismatch(h, other) == "the journal is of /prints/part.gcode, not /prints/other.gcode");
  InputIdentity grown = file;
  grown.size = 1200;
  CHECK(input_mismatch(h, grown) == "/prints/part.gcode changed since the print: 1000 bytes then, 1200 now");
  InputIdentity touched = file;
  touched.mtime_ns += 1;
  CHECK(input_mismatch(h, touched).find("modified since the print") != std::string::npos);
  InputIdentity stream{"-", false, 0, 0};
  CHECK(input_mismatch(h, stream) == "the journal is of the file /prints/part.gcode, not a stream");

  // A stream is told by its hash as it is read again, not here.
  JournalFields hs = journal_header(stream, "virtual");
  CHECK(input_mismatch(hs, stream).empty());
  CHECK(input_mismatch(hs, file) == "the journal is of a stream (-), not a file");
}
