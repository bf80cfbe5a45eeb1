#pragma once
// The command-line front end every gc tool shares: the same options for the
// same meaning, the same messages, the same exit statuses (a user who
// learned one tool knows the others).
//
//   gc-NAME [options] [FILE]     FILE '-' or absent: standard input
//   -o FILE, -i/--in-place (atomic), -q, -v, --layer-marker REGEX,
//   --layers/--z-range/--types where a tool works on part of a print,
//   --help, --version (the CMake project version).
//
// Exit statuses: 0 done; 1 the input cannot meet the request, or an I/O
// error ("gc-NAME: message"); 2 a usage error ("gc-NAME: message (see
// gc-NAME --help)"); a closed output pipe ends the tool as cat ends: by
// SIGPIPE, quietly. With -i the file is replaced only when the tool succeeded.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_marker.hpp"
#include "gcode/pipeline/selection.hpp"

// CLI11 is only declared here: a tool's main that includes this header
// parses none of CLI11's 9,000 lines and generates none of its code (8 of
// a main's 10 CPU seconds). The option groups that define options
// (cli/src/*_options.cpp) include <CLI/CLI.hpp> themselves.
namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace gcode::cli {

// A request that makes no sense whatever the input: exit 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};
// A request the input cannot meet (layer 80 of a 60-layer file): exit 1.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The options a filter shares with every other filter.
struct FilterOptions {
  std::string file;          // FILE; "" or "-": standard input
  std::string output;        // -o FILE
  bool in_place = false;     // -i
  bool quiet = false;        // -q
  int verbose = 0;           // -v (repeatable)
  std::string layer_marker;  // --layer-marker REGEX
  std::string e_mode = "auto";  // --e-mode: for files that never say M82/M83
  std::string tool;          // the program's name, for messages (set by Tool)

  // -1 errors only, 0 warnings, 1 and more: information.
  int verbosity() const { return quiet ? -1 : verbose; }
  // The slicer markers, or the user's pattern (throws std::invalid_argument).
  LayerMarkers markers() const;
};

// Which of the shared options a tool takes.
enum FilterParts : unsigned {
  kInput = 1,        // FILE
  kOutput = 2,       // -o
  kInPlace = 4,      // -i (needs FILE)
  kVerbosity = 8,    // -q, -v
  kLayerMarker = 16, // --layer-marker
  kEMode = 32,       // --e-mode
  kFilter = kInput | kOutput | kInPlace | kVerbosity | kLayerMarker | kEMode,
};

class Tool {
 public:
  // `name` is the program name (gc-NAME); `description` the --help text.
  Tool(std::string name, std::string description);
  Tool(const Tool&) = delete;
  Tool& operator=(const Tool&) = delete;
  ~Tool();

  CLI::App& app() { return *app_; }
  const std::string& name() const { return name_; }

  void add_filter_options(FilterOptions& options, unsigned parts = kFilter);
  // --layers, --z-range, --types; `verb` completes the help: "Split only in".
  void add_selection(SelectionText& text, const std::string& verb);
  // A check of option combinations, run after parsing (throw UsageError).
  void check(std::function<void()> rule) { checks_.push_back(std::move(rule)); }

  // Parses the command line and runs `body` under the conventions above.
  int run(int argc, char** argv, const std::function<int()>& body);

  Diagnostics diagnostics(const FilterOptions& options) const { return Diagnostics(name_, options.verbosity()); }

 private:
  int usage_error(const std::string& message) const;

  std::string name_;
  std::unique_ptr<CLI::App> app_;
  std::vector<std::function<void()>> checks_;
  FilterOptions* filter_ = nullptr;
  unsigned parts_ = 0;
};

// A filter's whole main: a Tool named `name` with `description` as its
// --help, the options `add_options` adds, then `body` with them and the
// Diagnostics their -q/-v ask for, under Tool::run's conventions.
template <class Options>
int run_filter(int argc, char** argv, std::string name, std::string description, void (*add_options)(Tool&, Options&),
               const std::type_identity_t<std::function<int(Options&, Diagnostics&)>>& body) {
  Options options;
  Tool tool(std::move(name), std::move(description));
  add_options(tool, options);
  return tool.run(argc, argv, [&] {
    Diagnostics diag = tool.diagnostics(options.io);
    return body(options, diag);
  });
}

// Validators with one message style: "--retract: must be a number >= 0, not 'x'".
const CLI::Validator& positive();
const CLI::Validator& non_negative();
// A comma list of numbers given to `option` ("--z 1.2,3"), or a UsageError naming it.
std::vector<double> option_numbers(const std::string& text, const char* option);
// A --layer-marker pattern RE2 compiles.
const CLI::Validator& layer_marker_pattern();

// The version of the suite, the same in every tool (from CMake's project version).
const char* version();

}  // namespace gcode::cli
