#pragma once
// Parses a command line with a Tool the way a tool's main does, for tests of
// a tool's options (cli/*_options.hpp): the exit status, and what it said on
// standard error.
#include <string>
#include <vector>

#include "capture.hpp"
#include "gcode/cli/tool.hpp"

namespace gctest {

// `args` without the program name; the body does nothing (exit 0).
inline int parse_options(gcode::cli::Tool& tool, std::vector<std::string> args, std::string* err = nullptr) {
  args.insert(args.begin(), tool.name());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  int status = -1;
  std::string e = stderr_of([&] { status = tool.run(static_cast<int>(args.size()), argv.data(), [] { return 0; }); });
  if (err != nullptr) *err = e;
  return status;
}

}  // namespace gctest
