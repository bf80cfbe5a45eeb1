// The output conventions every filter keeps (design.md, "Conventions every
// tool follows"), checked the same way on each: -i that replaces the file
// only when the run succeeded, CRLF kept on the lines a tool inserts, a
// closed output pipe that ends a tool quietly, the pipes it reads and writes
// widened to 1 MB, and a run told to edit nothing
// that leaves every fixture's lines as they are (options, versions and usage
// errors of every tool: tests/consistency). The tools come from tools/*;
// a new one fails here until it is given a row below.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "test_support.hpp"

namespace fs = std::filesystem;
using gctest::quote;
using gctest::read_file;
using gctest::run;

namespace {

// How to make a filter change a file (inserting lines) and how to make it fail
// after it has started reading (an input error or a check of the whole input).
struct FilterCase {
  std::string changing;    // options that insert or replace lines
  std::string failing;     // options the input cannot meet
  bool in_place = true;    // takes -i/--in-place
  bool old_on_stdin = false;  // gc-relayer: FILE is the new print, the old one comes on stdin
  // Options under which the filter edits no line: it writes the input byte
  // for byte, or (inserts_lines) the input's lines with a few of its own among them.
  std::string untouched;
  bool inserts_lines = false;
  // Whether `untouched` applies to every fixture (the property test below).
  bool untouched_everywhere = true;
};

const std::map<std::string, FilterCase>& filters() {
  static const std::string picture = quote(gctest::fixture_path("images/gradient.png"));
  static const std::map<std::string, FilterCase> cases = {
      {"gc-layers", {"--extract 2-5", "--extract 500", true, false, "--extract 1-"}},
      // --park: not every file names its bed.
      {"gc-pause-at", {"--before-layer 5", "--before-layer 500", true, false, "-q --before-layer 2 --park 0,200", true}},
      {"gc-subdivide", {"--max 0.5", "--max 0.5 --types no-such-feature", true, false, "--max 1000"}},
      {"gc-speedup", {"--factor 2 --layers 2-4", "--factor 2 --types no-such-feature", true, false, "--factor 1"}},
      // Layer 2 replaced by itself: the seams into and out of it are inserted.
      {"gc-swap-layer", {"--repeat 3", "--repeat 500", true, false, "-q --layer 2 --with {file}", true}},
      // The file joined onto itself: one seam.
      {"gc-relayer", {"--at-z 5", "--at-z 500", false, true, "-q --at-layer 2", true}},
      // -q: the cube is no vase, and the note that says so is not what this checks.
      {"gc-litho",
       {"-q --height 20 --texture " + picture, "-q --height 20 --texture " + picture + " --types no-such-feature", true,
        false, "-q --height 20 --layers 100000- --texture " + picture, true}},
      {"gc-deform", {"-q --xyz 'x + 0.001*y' y z", "-q --xyz x y 'z - 5'", true, false, "-q --xyz x y z"}},
      // The cube is one object: leaving it out is refused after the file was read.
      // No option edits nothing on every file: --label writes a line at each
      // block and needs labels, --exclude needs two objects.
      {"gc-objects", {"--label klipper", "--exclude 0", true, false, "--label marlin", true, false}},
  };
  return cases;
}

// Tools that do not filter G-code (a sender, a printer model, a writer of
// new programs): they keep the conventions of options, messages and versions only.
const std::vector<std::string>& others() {
  static const std::vector<std::string> names = {"gc-send", "gc-virtual-printer", "gc-shape"};
  return names;
}

std::vector<std::string> tool_names() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(GC_FIXTURES_DIR) / ".." / ".." / "tools"))
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

const char* kFixture = "prusa_cube_0.2_mk3s_rel_zhop.gcode";

std::string crlf(const std::string& text) {
  std::string out;
  out.reserve(text.size() + text.size() / 20);
  for (char c : text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

// The command that runs `tool` with `options` on `path`.
std::string command(const std::string& tool, const FilterCase& c, const std::string& options, const std::string& path) {
  std::string line = gctest::tool_command(tool, options + " " + quote(path));
  if (c.old_on_stdin) line += " <" + quote(path);
  return line;
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Every G-code file the suite keeps: tests/fixtures and its pairs/.
std::vector<std::string> corpus_paths() {
  std::vector<std::string> paths;
  for (const std::string& name : gctest::fixture_names()) paths.push_back(gctest::fixture_path(name));
  for (const std::string& name : files_in(gctest::fixture_path("pairs")))
    if (fs::path(name).extension() == ".gcode") paths.push_back(gctest::fixture_path("pairs/" + name));
  return paths;
}

// How many lines of `out` are not `in`'s, if `in`'s lines all stand in `out`
// unchanged and in their order (a greedy match finds them if they do); -1 if not.
long inserted_lines(const std::string& in, const std::string& out) {
  std::size_t at = 0, from = 0;
  long inserted = 0;
  while (from < out.size()) {
    std::size_t end = std::min(out.find('\n', from), out.size() - 1) + 1;
    std::string_view line(out.data() + from, end - from);
    if (in.compare(at, line.size(), line) == 0 && (at + line.size() == in.size() || line.back() == '\n'))
      at += line.size();
    else
      ++inserted;
    from = end;
  }
  return at == in.size() ? inserted : -1;
}

std::string with_file(std::string options, const std::string& path) {
  std::size_t at = options.find("{file}");
  if (at != std::string::npos) options.replace(at, 6, quote(path));
  return options;
}

}  // namespace

TEST_CASE("every tool is covered by the conventions tests", "[conventions]") {
  for (const std::string& tool : tool_names()) {
    INFO(tool << ": give it a row in filters() or others() of test_conventions.cpp");
    bool known = filters().count(tool) > 0 || std::count(others().begin(), others().end(), tool) > 0;
    CHECK(known);
  }
}

TEST_CASE("conventions: -i with standard input is a usage error in the common format", "[conventions]") {
  // The version and the usage-error format of every tool: tests/consistency.
  for (const auto& [tool, c] : filters()) {
    if (!c.in_place) continue;
    std::regex format("^" + tool + ": [^\n]+ \\(see " + tool + " --help\\)\n$");
    gctest::RunResult r = run(gctest::tool_command(tool, c.changing + " -i -"), read_file(gctest::fixture_path(kFixture)));
    INFO(tool << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(std::regex_match(r.err, format));
    CHECK(r.out.empty());
  }
}

TEST_CASE("a --layer-marker pattern that does not compile is a usage error", "[conventions]") {
  std::size_t tools = 0;
  for (const auto& [tool, c] : filters()) {
    if (run(gctest::tool_command(tool, "--help")).out.find("--layer-marker") == std::string::npos) continue;
    ++tools;
    std::regex format("^" + tool + ": [^\n]*layer-marker[^\n]+ \\(see " + tool + " --help\\)\n$");
    gctest::RunResult r = run(gctest::tool_command(tool, c.changing + " --layer-marker '(' -"),
                              read_file(gctest::fixture_path(kFixture)));
    INFO(tool << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(std::regex_match(r.err, format));
    CHECK(r.out.empty());
  }
  CHECK(tools >= 5);
}

TEST_CASE("conventions: -i replaces the file only when the run succeeded and leaves no temp file", "[conventions]") {
  const std::string original = read_file(gctest::fixture_path(kFixture));
  for (const auto& [tool, c] : filters()) {
    if (!c.in_place) continue;
    INFO(tool);
    std::string dir = gctest::temp_dir();
    std::string path = dir + "/part.gcode";
    gctest::write_file(path, original);

    gctest::RunResult failed = run(command(tool, c, c.failing + " -i", path));
    INFO(failed.err);
    CHECK((failed.status == 1 || failed.status == 2));
    CHECK(read_file(path) == original);
    CHECK(files_in(dir) == std::vector<std::string>{"part.gcode"});

    gctest::RunResult expected = run(command(tool, c, c.changing, path));
    REQUIRE(expected.status == 0);
    gctest::RunResult done = run(command(tool, c, c.changing + " -i", path));
    CHECK(done.status == 0);
    CHECK(done.out.empty());
    CHECK(read_file(path) == expected.out);
    CHECK(read_file(path) != original);
    CHECK(files_in(dir) == std::vector<std::string>{"part.gcode"});
  }
}

TEST_CASE("every filter told to edit nothing leaves every line of every fixture byte for byte", "[conventions][property]") {
  const std::vector<std::string> paths = corpus_paths();
  REQUIRE(paths.size() >= 20);
  for (const auto& [tool, c] : filters()) {
    if (!c.untouched_everywhere) continue;
    // (A second copy of the file, gc-relayer's FILE or gc-swap-layer's --with,
    // is read in the E mode guessed for it as for the input: a file without
    // M82/M83 is relative on both sides, its E values untouched.)
    for (const std::string& path : paths) {
      INFO(tool << " " << c.untouched << " " << path);
      const std::string input = read_file(path);
      gctest::RunResult r = run(command(tool, c, with_file(c.untouched, path), path));
      INFO(r.err);
      REQUIRE(r.status == 0);
      if (!c.inserts_lines) {
        CHECK(r.out == input);
        continue;
      }
      long inserted = inserted_lines(input, r.out);
      CHECK(inserted > 0);  // the lines the filter writes of its own, all in one place or two
      CHECK(inserted < 50);
    }
  }
}

TEST_CASE("every filter writes the lines it inserts with the input's CRLF endings", "[conventions]") {
  const std::string original = crlf(read_file(gctest::fixture_path(kFixture)));
  for (const auto& [tool, c] : filters()) {
    INFO(tool);
    std::string path = gctest::temp_dir() + "/part.gcode";
    gctest::write_file(path, original);
    gctest::RunResult r = run(command(tool, c, c.changing, path));
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out != original);
    std::size_t bare = 0, lines = 0;
    for (std::size_t i = 0; i < r.out.size(); ++i) {
      if (r.out[i] != '\n') continue;
      ++lines;
      if (i == 0 || r.out[i - 1] != '\r') ++bare;
    }
    CHECK(lines > 1000);
    CHECK(bare == 0);
  }
}

namespace {

struct PipeSizes {
  int status = -1;
  std::string out;
  int in_size = 0, out_size = 0;
};

// Runs the shell command `command` (exec'd) with `input` on a pipe of its
// own for standard input and a pipe for standard output, and gives back the
// two pipes' sizes once it has ended (this process holds an end of each, so
// both outlive it).
PipeSizes run_on_pipes(const std::string& command, const std::string& input) {
  int in[2], out[2];
  REQUIRE(::pipe2(in, O_CLOEXEC) == 0);
  REQUIRE(::pipe2(out, O_CLOEXEC) == 0);
  std::fflush(nullptr);
  pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::dup2(in[0], 0);
    ::dup2(out[1], 1);
    ::execl("/bin/sh", "sh", "-c", ("exec " + command + " 2>/dev/null").c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(out[1]);
  // The input goes in beside the output coming out: either may fill its pipe.
  std::thread writer([&] {
    for (std::size_t at = 0; at < input.size();) {
      ssize_t n = ::write(in[1], input.data() + at, input.size() - at);
      if (n <= 0) break;
      at += static_cast<std::size_t>(n);
    }
    ::close(in[1]);
  });
  PipeSizes r;
  char buffer[1 << 16];
  for (ssize_t n; (n = ::read(out[0], buffer, sizeof buffer)) > 0;) r.out.append(buffer, static_cast<std::size_t>(n));
  writer.join();
  int status = 0;
  ::waitpid(child, &status, 0);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.in_size = ::fcntl(in[0], F_GETPIPE_SZ);
  r.out_size = ::fcntl(out[0], F_GETPIPE_SZ);
  ::close(in[0]);
  ::close(out[0]);
  return r;
}

}  // namespace

TEST_CASE("every filter widens the pipes it reads and writes to 1 MB, so a pipeline's filters run side by side",
          "[conventions]") {
  // (InputFile/OutputFile::widen_pipe: the pipeline of three on the bench's
  // file runs about a quarter faster than on 64 KB pipes.)
  const std::string path = gctest::fixture_path(kFixture);
  const std::string input = read_file(path);
  for (const auto& [tool, c] : filters()) {
    INFO(tool);
    std::string line = gctest::tool_command(tool, with_file(c.untouched, path));
    if (c.old_on_stdin) line += " " + quote(path);  // gc-relayer: FILE is the new print, stdin the old
    PipeSizes r = run_on_pipes(line, input);
    REQUIRE(r.status == 0);
    CHECK(!r.out.empty());
    CHECK(r.in_size == 1 << 20);
    CHECK(r.out_size == 1 << 20);
  }
}

TEST_CASE("every filter ends quietly when its output pipe closes early", "[conventions]") {
  // More than the 1 MB the filter widens its output pipe to, so the filter
  // is still writing when head exits.
  const std::string path = gctest::fixture_path("prusa_tshape_0.2_support_mk3s_brim.gcode");
  for (const auto& [tool, c] : filters()) {
    INFO(tool);
    std::string dir = gctest::temp_dir();
    std::string line = "bash -c " + quote("set -o pipefail; " + command(tool, c, c.changing, path) + " 2>" +
                                          quote(dir + "/err") + " | head -c 100 >/dev/null; echo $?");
    gctest::RunResult r = run(line);
    REQUIRE(r.status == 0);
    // Killed by SIGPIPE as cat is (141), or done before it came (0): never an error message.
    CHECK((r.out == "141\n" || r.out == "0\n"));
    CHECK(read_file(dir + "/err").empty());
  }
}
