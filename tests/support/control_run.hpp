#pragma once
// gc-send runs with a control FIFO on the in-process virtual printer, and
// what its executed-command log says: shared by the pause and swap tests.
#include <catch2/catch.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/machine_state.hpp"
#include "serial_check.hpp"
#include "test_support.hpp"

namespace gctest {

struct Executed {
  double time;
  long long number;
  std::string command;
};

// With `input` (the commands of the file sent): gc-send's own pace probes
// and questions, numbered among the file's, left out (serial_check.hpp's
// drop_own_lines).
inline std::vector<Executed> read_log(const std::string& path, const std::vector<SentCommand>* input = nullptr) {
  std::vector<Executed> out;
  std::string text = read_file(path);
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) {
    std::string_view s = raw.text;
    if (!s.empty() && s[0] == '#') continue;  // a note (a printer reset), no command
    std::size_t a = s.find('\t'), b = s.find('\t', a + 1);
    long long n = std::stoll(std::string(s.substr(a + 1, b - a - 1)));
    std::size_t c = b;
    for (int i = 0; i < 4; ++i) c = s.find('\t', c + 1);
    if (n < 0) continue;
    out.push_back({std::stod(std::string(s.substr(0, a))), n, std::string(s.substr(c + 1))});
  }
  if (input == nullptr) return out;
  std::size_t j = 0;
  std::vector<Executed> kept;
  for (Executed& e : out) {
    if (j < input->size() && e.command == (*input)[j].text) {
      ++j;
    } else if (e.command == "G1" || e.command == "M105") {
      continue;
    }
    kept.push_back(std::move(e));
  }
  return kept;
}

inline std::string without_f(std::string_view command) {
  gcode::Line line = gcode::Line::parse(command);
  std::string out;
  std::size_t start = 0;
  std::string_view code = line.code();
  // Words are separated by blanks; drop the F word.
  while (start < code.size()) {
    std::size_t end = code.find(' ', start);
    std::string_view word = code.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    if (!word.empty() && word[0] != 'F' && word[0] != 'f') {
      if (!out.empty()) out += ' ';
      out += word;
    }
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

// A number after `key` in gc-send's messages ("... after input line 123").
inline double number_after(const std::string& text, const std::string& key) {
  std::size_t p = text.find(key);
  if (p == std::string::npos) return -1;
  return std::stod(text.substr(p + key.size(), 24));
}

struct PauseRun {
  RunResult result;
  std::vector<Executed> log;
};

// gc-send on the in-process printer with a control FIFO; `script` runs once
// the FIFO is there, with $F the FIFO, $S the status file and $L the
// printer's log, and three shell functions that wait for an event (never for
// a time, which a busy machine stretches): `paused` (the status file says
// so), `at_layer N` (it shows layer N) and `executed N` (the printer has run
// N of the print's numbered commands). `bed`: how gc-send learns the bed
// ("": not at all, as for a file that does not say).
inline PauseRun send_with_control(const std::string& file, const std::string& printer, const std::string& args,
                           const std::string& script, const std::string& bed = "--bed 250x210") {
  std::string dir = temp_dir();
  std::string fifo = dir + "/control.fifo", status = dir + "/status.json", log = dir + "/executed.log";
  std::string cmd = "F=" + quote(fifo) + "; S=" + quote(status) + "; L=" + quote(log) + "\n" + quote(tool_path("gc-send")) +
                    " -v --port virtual:" + printer + ",log=" + log + " --control \"$F\" --status-file \"$S\" " + bed + " " + args +
                    " " + quote(file) +
                    " & p=$!\n" + wait_for_fifo(fifo) +
                    "paused() { " + wait_for_lines("\"$S\"", {.match = quote("\"state\": \"paused\"")}) + "}\n" +
                    "at_layer() { " + wait_for_lines("\"$S\"", {.match = "\"\\\"layer\\\": $1,\""}) + "}\n" +
                    "executed() { " + wait_for_lines("\"$L\"", {.match = numbered_log_line(), .at_least = "$1"}) + "}\n" +
                    script + "\nwait $p";
  PauseRun r;
  r.result = run(cmd);
  const std::vector<SentCommand> input = commands_of(read_file(file));
  r.log = read_log(log, &input);
  return r;
}

struct Checked {
  std::size_t prefix = 0;  // input commands before the block
  std::size_t block = 0;   // lines of the pause and resume blocks
};

// The executed commands are the input's with the blocks at one place:
// input commands [0, prefix) (F words may differ: the rush), the blocks,
// then input commands [prefix, end) (the first move may carry its F back),
// then M400. Returns where.
// `speed_after`: a speed change follows the resume (F words may differ).
inline Checked check_one_pause(const std::vector<Executed>& log, const std::vector<SentCommand>& input,
                        std::uint64_t last_input_line, bool speed_after = false) {
  Checked c;
  while (c.prefix < input.size() && input[c.prefix].source_line <= last_input_line) ++c.prefix;
  REQUIRE(log.size() > input.size());
  c.block = log.size() - 1 - input.size();
  for (std::size_t i = 0; i < c.prefix; ++i) {
    INFO("before the block, command " << i);
    REQUIRE(without_f(log[i].command) == without_f(input[i].text));
  }
  for (std::size_t i = c.prefix; i < input.size(); ++i) {
    INFO("after the block, command " << i);
    const std::string& got = log[i + c.block].command;
    if (i < c.prefix + 3 || speed_after) {
      REQUIRE(without_f(got) == without_f(input[i].text));
    } else {
      REQUIRE(got == input[i].text);
    }
  }
  CHECK(log.back().command == "M400");
  for (std::size_t i = 1; i < log.size(); ++i) REQUIRE(log[i].number > log[i - 1].number);
  return c;
}

inline gcode::MachineState state_after(const std::vector<Executed>& log, std::size_t count) {
  gcode::MachineState s;
  for (std::size_t i = 0; i < count; ++i) s.apply(gcode::Line::parse(log[i].command));
  return s;
}

}  // namespace gctest
