// gc-send's control channel (gcode/serial/control/control_fifo.hpp): commands one per
// line, several per write, partial lines kept, junk dropped and reported once;
// the FIFO refused when it is not one, is another user's or can be written by
// others; opened so that nothing a writer does blocks the reader.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <vector>

#include "gcode/serial/control/control_fifo.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

namespace {

struct Collected {
  std::vector<ControlCommand> commands;
  std::vector<std::string> junk;
  ControlParser parser{[this](const ControlCommand& c) { commands.push_back(c); },
                       [this](std::string_view why) { junk.emplace_back(why); }};
};

}  // namespace

TEST_CASE("control: every command and its argument", "[serial][control]") {
  CHECK(parse_control_command("pause").is("pause"));
  CHECK(parse_control_command("  PAUSE  now ").is("pause now"));
  CHECK(parse_control_command("resume").is("resume"));
  CHECK(parse_control_command("cancel").is("cancel"));
  CHECK(parse_control_command("status\r").is("status"));
  ControlCommand s = parse_control_command("speed 1.5");
  CHECK(s.is("speed"));
  CHECK(s.number == 1.5);
  ControlCommand g = parse_control_command("gcode G1 Z10 F600 ; up");
  CHECK(g.is("gcode"));
  CHECK(g.argument == "G1 Z10 F600 ; up");
  CHECK(parse_control_command("swap /tmp/b.gcode").argument == "/tmp/b.gcode");
  CHECK(parse_control_command("insert part.gcode").is("insert"));
}

TEST_CASE("control: bad commands are Unknown with a reason, never an exception", "[serial][control]") {
  for (const char* bad : {"pasue", "speed", "speed fast", "speed 0", "speed -2", "speed 1e9", "gcode", "pause later",
                          "resume now", "swap", "42"}) {
    INFO(bad);
    ControlCommand c = parse_control_command(bad);
    CHECK(c.verb == nullptr);
    CHECK(!c.argument.empty());
  }
}

TEST_CASE("control: several commands per write, a line split over writes, blank lines", "[serial][control]") {
  Collected c;
  c.parser.feed("pause\nres");
  REQUIRE(c.commands.size() == 1);
  c.parser.feed("ume\n\n\nspeed 2\r\nstat");
  REQUIRE(c.commands.size() == 3);
  CHECK(c.commands[1].is("resume"));
  CHECK(c.commands[2].is("speed"));
  c.parser.feed("us\n");
  REQUIRE(c.commands.size() == 4);
  CHECK(c.commands[3].is("status"));
  CHECK(c.junk.empty());
}

TEST_CASE("control: a megabyte of junk is dropped and reported once, and the next good line works", "[serial][control]") {
  Collected c;
  std::string junk;
  for (int i = 0; i < (1 << 20); ++i) junk += static_cast<char>((static_cast<unsigned>(i) * 7919u) & 0xffu);
  for (std::size_t at = 0; at < junk.size(); at += 4096) c.parser.feed(std::string_view(junk).substr(at, 4096));
  c.parser.feed("\npause\n");
  CHECK(c.junk.size() == 1);
  CHECK(c.parser.junk_bytes() > 1000000);
  // Whatever the junk held between its newlines was dropped or Unknown: only the last line is a pause.
  REQUIRE(!c.commands.empty());
  CHECK(c.commands.back().is("pause"));
  for (std::size_t i = 0; i + 1 < c.commands.size(); ++i) CHECK(c.commands[i].verb == nullptr);
  // A new run of junk after a good line is reported again.
  c.parser.feed(std::string(ControlParser::kMaxLine + 10, 'x'));
  c.parser.feed("\nresume\n");
  CHECK(c.junk.size() == 2);
  CHECK(c.commands.back().is("resume"));
}

TEST_CASE("control: default path under XDG_RUNTIME_DIR, named after the port", "[serial][control]") {
  std::string old = std::getenv("XDG_RUNTIME_DIR") != nullptr ? std::getenv("XDG_RUNTIME_DIR") : "";
  setenv("XDG_RUNTIME_DIR", "/run/user/1000", 1);
  CHECK(default_control_path("/dev/ttyACM0") == "/run/user/1000/gc-send/ttyACM0.fifo");
  CHECK(default_control_path("virtual:time-scale=20") == "/run/user/1000/gc-send/virtual.fifo");
  unsetenv("XDG_RUNTIME_DIR");
  CHECK(default_control_path("/dev/ttyUSB1").rfind("/tmp/gc-send-", 0) == 0);
  if (!old.empty()) setenv("XDG_RUNTIME_DIR", old.c_str(), 1);
}

TEST_CASE("control: a regular file, a group- or other-writable FIFO, another user's FIFO are refused",
          "[serial][control]") {
  std::string dir = gctest::temp_dir();
  std::string file = dir + "/regular.fifo";
  gctest::write_file(file, "pause\n");
  CHECK_THROWS_WITH(ControlFifo(file), Catch::Contains("not a FIFO"));
  std::string group = dir + "/group.fifo";
  REQUIRE(mkfifo(group.c_str(), 0600) == 0);
  chmod(group.c_str(), 0620);
  CHECK_THROWS_WITH(ControlFifo(group), Catch::Contains("its group"));
  chmod(group.c_str(), 0602);
  CHECK_THROWS_WITH(ControlFifo(group), Catch::Contains("others"));
  chmod(group.c_str(), 0600);
  CHECK(control_path_problem(group, getuid()).empty());
  // Another owner: the same check with another uid (a test cannot chown).
  CHECK_THAT(control_path_problem(group, getuid() + 1), Catch::Contains("another user"));
  std::string link = dir + "/link.fifo";
  REQUIRE(symlink(group.c_str(), link.c_str()) == 0);
  CHECK_THROWS_WITH(ControlFifo(link), Catch::Contains("not a FIFO"));
}

TEST_CASE("control: created 0600, never blocks: a silent writer, a closed writer, half a line", "[serial][control]") {
  std::string dir = gctest::temp_dir();
  std::string path = dir + "/sub/printer.fifo";
  Collected c;
  {
    ControlFifo fifo(path);
    struct stat st{};
    REQUIRE(stat(path.c_str(), &st) == 0);
    CHECK(S_ISFIFO(st.st_mode));
    CHECK((st.st_mode & 0777) == 0600);
    auto start = std::chrono::steady_clock::now();
    fifo.read_into(c.parser);  // nothing written: returns at once
    int silent = open(path.c_str(), O_WRONLY | O_NONBLOCK);  // opens and never writes
    REQUIRE(silent >= 0);
    fifo.read_into(c.parser);
    int w = open(path.c_str(), O_WRONLY | O_NONBLOCK);
    REQUIRE(write(w, "pause\nres", 9) == 9);
    close(w);  // a writer that closes: no end of file for the reader
    fifo.read_into(c.parser);
    w = open(path.c_str(), O_WRONLY | O_NONBLOCK);
    REQUIRE(write(w, "ume\n", 4) == 4);
    close(w);
    fifo.read_into(c.parser);
    close(silent);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
    REQUIRE(c.commands.size() == 2);
    CHECK(c.commands[0].is("pause"));
    CHECK(c.commands[1].is("resume"));
  }
  CHECK(access(path.c_str(), F_OK) != 0);  // made by it, removed by it
}

TEST_CASE("control: a FIFO in a folder others may write to is refused", "[serial][control]") {
  std::string dir = gctest::temp_dir() + "/shared";
  REQUIRE(mkdir(dir.c_str(), 0777) == 0);
  chmod(dir.c_str(), 0777);  // writable by all, not sticky: the FIFO could be swapped
  CHECK_THROWS_WITH(ControlFifo(dir + "/p.fifo"), Catch::Contains("can be changed by others"));
  chmod(dir.c_str(), 01777);  // sticky, like /tmp: only owners remove their files
  CHECK_NOTHROW(ControlFifo(dir + "/p.fifo"));
}
