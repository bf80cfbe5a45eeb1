#pragma once
// Messages to stderr in the form every gc tool uses: "gc-NAME: line 12: ...".
// Warnings about bad input are counted; after the first few only the count is
// reported, so a file full of junk does not flood the terminal.
#include <cstdint>
#include <string>
#include <string_view>

namespace gcode {

class Diagnostics {
 public:
  explicit Diagnostics(std::string tool, int verbosity = 0, int max_warnings = 20)
      : tool_(std::move(tool)), verbosity_(verbosity), max_warnings_(max_warnings) {}
  ~Diagnostics();  // prints how many warnings were not shown

  // verbosity: -1 quiet (errors only), 0 warnings, 1 info (-v).
  void set_verbosity(int v) { verbosity_ = v; }
  int verbosity() const { return verbosity_; }
  void warn(std::uint64_t line_number, std::string_view message);
  void warn(std::string_view message) { warn(0, message); }
  void info(std::string_view message);
  void error(std::string_view message);
  // A line the user asked for (a summary, a progress line, the -vv trace):
  // printed whatever the verbosity, the caller decides when. It ends at a
  // NUL byte: a printer's line noise is cut there, as printf always cut it.
  void report(std::string_view message);
  std::uint64_t warnings() const { return warnings_; }
  const std::string& tool() const { return tool_; }

 private:
  std::string tool_;
  int verbosity_;
  int max_warnings_;
  std::uint64_t warnings_ = 0;
};

}  // namespace gcode
