#pragma once
// Helpers shared by the tests: fixture paths, reading files, running a built
// tool, and replaying G-code through the library into plain records that
// tests compare (the "independent checker" of the tool tests).
#include <set>

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/core/machine_state.hpp"
#include "gcode/pipeline/pipeline.hpp"
#include "gcode/transform/subdivide.hpp"

namespace gctest {

// Whether the tree is built with the sanitizers: gc-send's timing figures
// (pause now's distance, pacing against --no-pace) are defined for the
// tools as users build them, and are checked only there; the instrumented
// tree runs the same prints and checks that they come out exact.
inline constexpr bool kTimingFiguresChecked = GC_INSTRUMENTED == 0;

// Numbers written as the library writes them by default (stages keep a
// reference to it: it lives as long as the program).
inline const gcode::Precision kPrecision{};

std::string fixture_path(std::string_view name);
std::string tool_path(std::string_view tool);
std::string read_file(const std::string& path);
void write_file(const std::string& path, std::string_view data);
// The first `lines` lines of a fixture (a cut of its first layers).
std::string head_of(const std::string& name, std::size_t lines);
// All fixture file names (*.gcode) in tests/fixtures.
std::vector<std::string> fixture_names();
// The layers the slicer itself says a fixture has (layer_count, z, ...), from
// tests/fixtures/expected/<name without .gcode>.json, or null where a fixture
// has none. tests/fixtures/sources/README.md says how each was derived.
nlohmann::json expected_data(std::string_view fixture);
// A file opened for reading, closed at the end of the scope (for pieces that
// take a descriptor).
class OpenedFile {
 public:
  explicit OpenedFile(const std::string& path);
  ~OpenedFile();
  OpenedFile(const OpenedFile&) = delete;
  OpenedFile& operator=(const OpenedFile&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

// A fresh empty directory under the build's temp area.
std::string temp_dir();

struct RunResult {
  int status = -1;      // exit status, or 128+signal
  std::string out;
  std::string err;
};
// Runs a shell command line (arguments already quoted), feeding `input` on stdin.
RunResult run(const std::string& command_line, std::string_view input = {});
std::string quote(std::string_view arg);
// A shell snippet that polls the shell test `condition` up to `tries`
// times, `pause` seconds apart, and goes on once it holds (or after the
// last try: the test's own checks then say what did not happen).
std::string wait_until(const std::string& condition, int tries = 1000, double pause = 0.01);
// A shell snippet that waits until `file` has `at_least` complete lines
// (default 1) matching `match` (a basic regular expression, as grep's;
// default: any line), counted from the first line matching `after` on
// (which must be there, even for at_least 0), up
// to `tries` x `every` seconds, and no longer than process `while_alive`
// lives. Then the script goes on, as after wait_until. Every field but
// the numbers is a shell word as the script writes it (quote() a literal);
// empty: not given. One process (gctest-wait, support/programs/gctest_wait.cpp)
// reads what the file gained each turn, where a shell loop would start a
// grep and a sleep.
struct LinesWait {
  std::string match = {}, after = {}, at_least = {}, while_alive = {};
  int tries = 1000;
  double every = 0.01;
};
std::string wait_for_lines(const std::string& file, const LinesWait& wait);
// The virtual printer's log lines of numbered commands (a number, not -1,
// in the second column): the print's own, not gc-send's questions (M110,
// M115, M114) or the pacer's moves of no length. A shell word, for
// wait_for_lines' `match` or `grep -c`.
std::string numbered_log_line();
// A shell command that prints how many such lines the log at `log` holds.
std::string numbered_log_count(const std::string& log);
// ... until gc-send's journal at `journal` holds its first acknowledged
// line (up to 10 s; no longer than process `while_alive` lives, if given):
// a loaded machine can take a second to start gc-send and open the printer,
// and a kill timed from before that leaves nothing to resume.
std::string wait_for_journal_start(const std::string& journal, const std::string& while_alive = "");
// ... until gc-send made its control FIFO at `path` (up to 10 s): written
// before, `echo pause > path` makes a regular file, which gc-send then
// refuses (a loaded machine starts gc-send late).
std::string wait_for_fifo(const std::string& path);
// ... until gc-virtual-printer made its pty's link at `path` (up to 5 s).
std::string wait_for_link(const std::string& path);
// The shell command line that runs a built tool with `args` (already quoted).
std::string tool_command(std::string_view tool, const std::string& args);

// Every "--name" in a text: --help output or a man page (roff writes a dash
// as "\-"), for tests that the two name the same options.
std::set<std::string> long_options(std::string text);

// Splits text into lines the way the library does (endings kept).
std::vector<std::string> split_lines(std::string_view text);

// One motion command replayed through MachineState.
struct ReplayedMove {
  gcode::Move move;
  gcode::MachineState after;
  std::size_t line_index;  // 0-based line in the text
};
// The state a file starts from, as its slicer meant it: for a file that
// never says M82/M83, the E mode its config or its E values show (the
// library's e_mode.hpp; the fixtures' expected data checks that reading).
gcode::MachineState initial_state(std::string_view text);
// `err` without the one warning a tool gives on a file that never sets its
// E mode (that warning is expected there; anything else is not).
std::string without_e_mode_warning(const std::string& err);
std::vector<ReplayedMove> replay_moves(std::string_view text);
// How many M82/M83 (E mode) commands a text holds.
int e_mode_commands(std::string_view text);
gcode::MachineState replay_state(std::string_view text);

// Per input line, its layer (0 outside layers), its ;TYPE: feature and the
// Z of its layer, as the tracker (gc-layers' numbering) sees them.
struct LinePlace {
  std::vector<int> layer;
  std::vector<std::string> feature;
  std::vector<double> layer_z;
};
LinePlace places_of(const std::string& text);

// Runs `text` through `stages` and a GcodeWriter; returns what was written.
// `layers`: track layers (else every line is start code).
std::string run_stages(std::string_view text, std::initializer_list<gcode::Stage*> stages, bool layers = true);
// The same with a pipeline the caller set up (its stages added, no writer yet).
std::string run_stages(gcode::Pipeline& pipeline, std::string_view text);
// `text` through the Subdivider, line by line as gc-subdivide runs it.
struct Subdivided {
  std::string text;
  gcode::SubdivideStats stats;
};
Subdivided subdivide(std::string_view text, const gcode::SubdivideOptions& options,
                     gcode::Diagnostics* diagnostics = nullptr);
// `text` with every move cut into pieces of at most `max_length` mm (gc-subdivide --max).
std::string subdivided(std::string_view text, double max_length);

}  // namespace gctest
