#pragma once
// Bash completion generated from a tool's own option definitions, so it
// cannot drift from --help: every tool answers the hidden option
// `--bash-completion` with the script, and the build writes it to
// share/bash-completion/completions/gc-NAME (bash-completion loads it the
// first time gc-NAME<TAB> is pressed).
//
// What it completes: option names after "-"; after an option that takes a
// value, the value's choices where the option checks them (CLI::IsMember:
// --e-mode auto|relative|absolute), file names where the value is a file
// (its type name says FILE, PATH, IMAGE, ...), nothing where it is a number;
// file names for the positional FILE.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace gcode::cli {

// What completion knows about one option.
struct CompletionEntry {
  std::vector<std::string> names;    // "-o", "--output"
  bool takes_value = false;
  bool file_value = false;           // complete the value as a file name
  std::vector<std::string> choices;  // the values the option accepts, if it lists them
};

// The options `app` defines that --help shows (hidden ones left out).
std::vector<CompletionEntry> completion_entries(const CLI::App& app);

// A bash script defining and registering the completion of `program`.
std::string bash_completion(const std::string& program, const std::vector<CompletionEntry>& entries);

}  // namespace gcode::cli
