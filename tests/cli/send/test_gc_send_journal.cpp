// gc-send's journal as the tool writes it (docs/gc-send-journal.md): a print
// on the built-in virtual printer leaves a journal that reads back, names
// the input, holds the machine state after the last command and is marked
// finished; a killed gc-send leaves one that reads back unfinished; the
// default path, --no-journal, the file's mode and the folder check.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <string>

#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/journal/journal_point.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::run;
using gctest::tool_path;

namespace {

std::string send_command(const std::string& args) { return quote(tool_path("gc-send")) + " " + args; }

}  // namespace

TEST_CASE("gc-send journal: a finished print reads back, marked finished, with the input's last state", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string text = gctest::head_of("prusa_cube_0.2_mk3s_rel_zhop.gcode", 1500);
  std::string input = dir + "/part.gcode";
  gctest::write_file(input, text);
  std::string journal = dir + "/part.journal";
  auto r = run(send_command("--port virtual:time-scale=200 --journal " + quote(journal) + " " + quote(input)));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("gc-send: journal " + journal + ": ") != std::string::npos);

  struct stat st{};
  REQUIRE(::stat(journal.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);

  gcode::serial::JournalContents c = gcode::serial::read_journal(journal);
  CHECK(c.finished);
  CHECK_FALSE(c.torn_tail);
  CHECK(c.header.get("regular") == "1");
  CHECK(c.header.get("size") == std::to_string(text.size()));
  CHECK(c.header.get("input").find("/part.gcode") != std::string::npos);
  CHECK(c.header.get("input").front() == '/');  // absolute: a resume may run from another folder
  REQUIRE_FALSE(c.entries.empty());
  // Every line sent is in it, numbered 1.. in order (gc-send's own
  // questions and pace probes marked "ask"), and the printer acknowledged
  // the last of them (M400).
  auto commands = gctest::commands_of(text);
  std::vector<const gcode::serial::JournalEntry*> of_commands;
  for (const auto& e : c.entries)
    if (e.point.get("ask") != "1") of_commands.push_back(&e);
  CHECK(of_commands.size() == commands.size() + 1);
  CHECK(c.acknowledged == c.entries.back().n);
  for (std::size_t i = 1; i < c.entries.size(); ++i) CHECK(c.entries[i].n == c.entries[i - 1].n + 1);
  // The commands whose answer means every one before them ran (the start
  // code's G28, the closing M400) are marked drained, and only they: a
  // walk back after a reset stops there.
  std::size_t drained = 0;
  for (std::size_t i = 0; i < of_commands.size(); ++i) {
    if (!gcode::serial::is_drained(of_commands[i]->point)) continue;
    ++drained;
    const std::string command = i + 1 < of_commands.size() ? commands[i].text : "M400";
    INFO(command);
    CHECK((command.starts_with("G28") || command.starts_with("M400") || command.starts_with("G29") ||
           command.starts_with("G4")));
  }
  CHECK(drained >= 2);
  CHECK(gcode::serial::is_drained(c.entries.back().point));
  // The entry of the input's last command names its line and the end of
  // it, and holds the state the input leaves the machine in.
  const gcode::serial::JournalEntry& last = *of_commands[of_commands.size() - 2];
  CHECK(last.point.get("line") == std::to_string(commands.back().source_line));
  std::size_t end = 0;
  for (std::uint64_t l = 0; l < commands.back().source_line; ++l) end = text.find('\n', end) + 1;
  CHECK(last.point.get("off") == std::to_string(end));
  gcode::MachineState state;
  std::string problem;
  REQUIRE(gcode::serial::read_machine_fields(last.point, state, problem));
  gcode::MachineState expected = gctest::replay_state(text);
  for (int a = 0; a < 4; ++a) CHECK(state.at(a) == expected.at(a));
  CHECK(state.relative_e == expected.relative_e);
  CHECK(state.hotend_target[0] == expected.hotend_target[0]);
  CHECK(state.bed_target == expected.bed_target);
  CHECK(last.point.get("layer") != "0");
}

TEST_CASE("gc-send journal: SIGKILL mid-print leaves a journal that reads back, not finished", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string journal = dir + "/j.journal";
  std::string file = gctest::fixture_path("prusa_cube_0.2_mk3s_rel_zhop.gcode");
  auto r = run(send_command("-q --port virtual:time-scale=20 --journal " + quote(journal) + " " + quote(file)) +
               " & p=$!; sleep 1.5; kill -9 $p; wait $p");
  CHECK(r.status == 128 + 9);
  gcode::serial::JournalContents c = gcode::serial::read_journal(journal);
  CHECK_FALSE(c.finished);
  REQUIRE(c.entries.size() > 10);
  CHECK(c.acknowledged > 0);
  CHECK(c.acknowledged <= c.entries.back().n);
}

TEST_CASE("gc-send journal: the default path, --no-journal, and a folder others can write", "[gc-send]") {
  std::string dir = gctest::temp_dir();
  std::string state = dir + "/state";
  std::string input = "G28\nG1 X10 Y10 F6000\n";
  std::string env = "XDG_STATE_HOME=" + quote(state) + " ";

  // The built-in virtual printer ends with gc-send: no journal unless asked for.
  auto r = run("cat | " + env + send_command("-q --port virtual:time-scale=50"), input);
  CHECK(r.status == 0);
  struct stat st{};
  CHECK(::stat(state.c_str(), &st) != 0);

  std::string path = state + "/gc-send/virtual.journal";
  r = run("cat | " + env + send_command("-q --port virtual:time-scale=50 --journal " + quote(path)), input);
  INFO(r.err);
  CHECK(r.status == 0);
  gcode::serial::JournalContents c = gcode::serial::read_journal(path);
  CHECK(c.finished);
  CHECK(c.header.get("input") == "-");
  CHECK(c.header.get("regular") == "0");
  REQUIRE(::stat((state + "/gc-send").c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0700);

  std::string other = dir + "/other";
  r = run(env + "XDG_STATE_HOME=" + quote(other) + " " + send_command("-q --no-journal --port virtual:time-scale=50"),
          input);
  CHECK(r.status == 0);
  CHECK(::stat(other.c_str(), &st) != 0);

  // A folder anyone may write to (and not sticky): refused before anything is sent.
  std::string open_dir = dir + "/open";
  REQUIRE(::mkdir(open_dir.c_str(), 0700) == 0);
  REQUIRE(::chmod(open_dir.c_str(), 0777) == 0);
  std::string vlog = dir + "/executed.log";
  r = run(send_command("-q --port virtual:time-scale=50,log=" + quote(vlog) + " --journal " +
                       quote(open_dir + "/x.journal")),
          input);
  CHECK(r.status == 1);
  CHECK(r.err.find("journal refused: its folder " + open_dir + " can be changed by others") != std::string::npos);
  CHECK(::stat(vlog.c_str(), &st) != 0);  // the printer was not even opened
  CHECK(::stat((open_dir + "/x.journal").c_str(), &st) != 0);
}
