// gc-send --resume (gcode/serial/job/send_resume.hpp): the command that
// goes on with a print, as gc-send says it, and a journal that is not there
// refused before anything is sent.
#include <catch2/catch.hpp>

#include <string>

#include "gcode/serial/job/send_resume.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("send resume: the command that goes on with a print", "[serial][send_resume]") {
  CHECK(resume_command("/s/print.journal", "/p/part.gcode", "/dev/ttyACM0") ==
        "gc-send --resume /s/print.journal /p/part.gcode --port /dev/ttyACM0");
  const std::string spaced = resume_command("/s/print.journal", "/p/my part.gcode", "/dev/ttyACM0");
  CHECK(spaced.find("'/p/my part.gcode'") != std::string::npos);
  CHECK(resume_command("/s/print.journal", "-", "/dev/ttyACM0").rfind("(the same pipeline) | gc-send --resume", 0) == 0);
}

TEST_CASE("send resume: a journal that is not there is refused", "[serial][send_resume]") {
  CHECK_THROWS_AS(open_resume(gctest::temp_dir() + "/no-such.journal", ""), ResumeError);
}
