#pragma once
// Helpers shared by the tests: fixture paths, reading files, running a built
// tool, and replaying G-code through the library into plain records that
// tests compare (the "independent checker" of the tool tests).
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/machine_state.hpp"
#include "gcode/pipeline/pipeline.hpp"

namespace gctest {

std::string fixture_path(std::string_view name);
std::string tool_path(std::string_view tool);
std::string read_file(const std::string& path);
void write_file(const std::string& path, std::string_view data);
// All fixture file names (*.gcode) in tests/fixtures.
std::vector<std::string> fixture_names();
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
// The shell command line that runs a built tool with `args` (already quoted).
std::string tool_command(std::string_view tool, const std::string& args);

// Every long option ("--name") in a --help text or a man page (roff writes a
// dash as "\-"), for checking that the two name the same options.
std::set<std::string> long_options(std::string text);

// Splits text into lines the way the library does (endings kept).
std::vector<std::string> split_lines(std::string_view text);

// One motion command replayed through MachineState.
struct ReplayedMove {
  gcode::Move move;
  gcode::MachineState after;
  std::size_t line_index;  // 0-based line in the text
};
std::vector<ReplayedMove> replay_moves(std::string_view text);
gcode::MachineState replay_state(std::string_view text);

// Runs `text` through `stages` and a GcodeWriter; returns what was written.
// `layers`: track layers (else every line is start code).
std::string run_stages(std::string_view text, std::initializer_list<gcode::Stage*> stages, bool layers = true);
// The same with a pipeline the caller set up (its stages added, no writer yet).
std::string run_stages(gcode::Pipeline& pipeline, std::string_view text);

}  // namespace gctest
