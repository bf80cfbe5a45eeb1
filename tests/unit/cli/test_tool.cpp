// The command-line front end (cli/tool.hpp): exit statuses (0; 1 for input
// and I/O errors; 2 for usage errors, with "(see gc-NAME --help)"; a closed
// pipe as SIGPIPE), the shared options and their rules, validators with one
// message style, --version from the CMake project version.
#include <CLI/CLI.hpp>
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/cli/tool.hpp"
#include "gcode/core/output_buffer.hpp"
#include "capture.hpp"

using gcode::cli::FilterOptions;
using gcode::cli::Tool;

namespace {

struct ToolOutcome {
  int status = -1;
  std::string out, err;
};

// Runs `tool` on `args` (without the program name) with `body`.
ToolOutcome run(Tool& tool, std::vector<std::string> args, const std::function<int()>& body = [] { return 0; }) {
  args.insert(args.begin(), tool.name());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ToolOutcome o;
  o.err = gctest::stderr_of([&] { o.out = gctest::stdout_of([&] { o.status = tool.run(static_cast<int>(args.size()), argv.data(), body); }); });
  return o;
}

}  // namespace

TEST_CASE("tool: what the body throws decides the exit status and message", "[tool]") {
  Tool tool("gc-test", "A test tool");
  CHECK(run(tool, {}, [] { return 0; }).status == 0);
  CHECK(run(tool, {}, [] { return 3; }).status == 3);
  ToolOutcome usage = run(tool, {}, []() -> int { throw gcode::cli::UsageError("--every needs a number"); });
  CHECK(usage.status == 2);
  CHECK(usage.err == "gc-test: --every needs a number (see gc-test --help)\n");
  ToolOutcome input = run(tool, {}, []() -> int { throw gcode::cli::InputError("--before-layer 80: the file has 60 layers"); });
  CHECK(input.status == 1);
  CHECK(input.err == "gc-test: --before-layer 80: the file has 60 layers\n");
  ToolOutcome io = run(tool, {}, []() -> int { throw std::runtime_error("x.gcode: No such file or directory"); });
  CHECK(io.status == 1);
  CHECK(io.err == "gc-test: x.gcode: No such file or directory\n");
}

TEST_CASE("tool: a closed output pipe ends the tool by SIGPIPE, quietly", "[tool]") {
  std::fflush(nullptr);
  pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    Tool tool("gc-test", "A test tool");
    char name[] = "gc-test";
    char* argv[] = {name, nullptr};
    int status = tool.run(1, argv, []() -> int { throw gcode::BrokenPipe(); });
    ::_exit(status == 141 ? 99 : 98);  // not reached: the signal ends the process
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGPIPE);
}

TEST_CASE("tool: the shared filter options", "[tool]") {
  Tool tool("gc-test", "A test tool");
  FilterOptions o;
  tool.add_filter_options(o);
  CHECK(o.tool == "gc-test");
  ToolOutcome ok = run(tool, {"-o", "out.gcode", "-vv", "--layer-marker", "^L(\\d+)", "--e-mode", "relative", "in.gcode"});
  CHECK(ok.status == 0);
  CHECK(o.file == "in.gcode");
  CHECK(o.output == "out.gcode");
  CHECK(o.verbose == 2);
  CHECK(o.verbosity() == 2);
  CHECK(o.layer_marker == "^L(\\d+)");
  CHECK(o.e_mode == "relative");
  FilterOptions q;
  q.quiet = true;
  q.verbose = 1;
  CHECK(q.verbosity() == -1);
  FilterOptions bad;
  bad.layer_marker = "(";
  CHECK_THROWS_AS(bad.markers(), std::invalid_argument);
  CHECK_NOTHROW(FilterOptions{}.markers());
}

TEST_CASE("tool: usage errors exit 2 in one message style", "[tool]") {
  auto usage = [](std::vector<std::string> args, unsigned parts = gcode::cli::kFilter) {
    Tool tool("gc-test", "A test tool");
    FilterOptions o;
    tool.add_filter_options(o, parts);
    tool.check([&] {
      if (o.output == "forbidden") throw gcode::cli::UsageError("-o forbidden: no");
    });
    bool ran = false;
    ToolOutcome r = run(tool, std::move(args), [&] {
      ran = true;
      return 0;
    });
    CHECK_FALSE(ran);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("gc-test: ", 0) == 0);
    CHECK(r.err.size() > 30);
    const std::string tail = " (see gc-test --help)\n";
    CHECK(r.err.substr(r.err.size() - tail.size()) == tail);
    return r.err;
  };
  CHECK(usage({"-i"}) == "gc-test: -i/--in-place needs a FILE to rewrite, not standard input (see gc-test --help)\n");
  CHECK(usage({"-i", "-"}).find("needs a FILE") != std::string::npos);
  CHECK(usage({"-i", "-o", "x", "f.gcode"}).find("excludes") != std::string::npos);
  CHECK(usage({"--bogus"}).find("--bogus") != std::string::npos);
  CHECK(usage({"--e-mode", "sometimes"}).find("sometimes") != std::string::npos);
  CHECK(usage({"-o", "forbidden"}) == "gc-test: -o forbidden: no (see gc-test --help)\n");
  CHECK(usage({"-o", "x"}, gcode::cli::kInput).find("-o") != std::string::npos);  // not a part of this tool
}

TEST_CASE("tool: --layers, --z-range and --types are checked before the body", "[tool]") {
  auto status = [](std::vector<std::string> args, std::string* err = nullptr) {
    Tool tool("gc-test", "A test tool");
    gcode::SelectionText text;
    tool.add_selection(text, "Work only in");
    ToolOutcome r = run(tool, std::move(args));
    if (err != nullptr) *err = r.err;
    return r.status;
  };
  std::string err;
  CHECK(status({"--layers", "3-5", "--z-range", "0.2:", "--types", "FILL"}) == 0);
  CHECK(status({"--layers", "5-3"}, &err) == 2);
  CHECK(err == "gc-test: --layers: bad layer range '5-3': 5-3 runs backwards (see gc-test --help)\n");
  CHECK(status({"--z-range", "x:1"}, &err) == 2);
  CHECK(err.find("--z-range: bad Z range 'x:1'") != std::string::npos);
  CHECK(status({"--types", ","}, &err) == 2);
  CHECK(err == "gc-test: --types: give ;TYPE: names, e.g. WALL-OUTER (see gc-test --help)\n");
}

TEST_CASE("tool: validators share one message", "[tool]") {
  auto check = [](const std::string& value, bool positive, std::string* err) {
    Tool tool("gc-test", "A test tool");
    double v = 0;
    tool.app().add_option("--retract", v)->check(positive ? gcode::cli::positive() : gcode::cli::non_negative());
    ToolOutcome r = run(tool, {"--retract", value});
    *err = r.err;
    return r.status;
  };
  std::string err;
  CHECK(check("0.5", true, &err) == 0);
  CHECK(check("0", true, &err) == 2);
  CHECK(err == "gc-test: --retract: must be a number > 0, not '0' (see gc-test --help)\n");
  CHECK(check("0", false, &err) == 0);
  CHECK(check("-1", false, &err) == 2);
  CHECK(err == "gc-test: --retract: must be a number >= 0, not '-1' (see gc-test --help)\n");
  CHECK(check("abc", false, &err) == 2);
  CHECK(err.find("must be a number >= 0, not 'abc'") != std::string::npos);
  CHECK(check("inf", true, &err) == 2);
  CHECK(check("1e3", true, &err) == 0);
}

TEST_CASE("tool: --version is the CMake project version, --help exits 0", "[tool]") {
  std::ifstream cmake(std::string(GC_FIXTURES_DIR) + "/../../CMakeLists.txt");
  std::string text((std::istreambuf_iterator<char>(cmake)), std::istreambuf_iterator<char>());
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex(R"(project\(gcode-tools VERSION ([0-9.]+))")));
  CHECK(std::string(gcode::cli::version()) == m[1].str());
  Tool tool("gc-test", "A test tool");
  ToolOutcome v = run(tool, {"--version"}, []() -> int { throw std::logic_error("the body must not run"); });
  CHECK(v.status == 0);
  CHECK(v.out == "gc-test " + m[1].str() + "\n");
  ToolOutcome h = run(tool, {"--help"}, []() -> int { throw std::logic_error("the body must not run"); });
  CHECK(h.status == 0);
  CHECK(h.out.find("A test tool") != std::string::npos);
  CHECK(h.out.find("--version") != std::string::npos);
}
