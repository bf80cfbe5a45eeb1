// completion.hpp: what bash completion learns from a tool's option
// definitions (the script itself is tried in bash by tests/scripts/completion.sh).
#include <catch2/catch.hpp>

#include <algorithm>

#include "gcode/cli/completion.hpp"

using gcode::cli::CompletionEntry;

namespace {

const CompletionEntry* entry(const std::vector<CompletionEntry>& all, const std::string& name) {
  for (const CompletionEntry& e : all)
    if (std::find(e.names.begin(), e.names.end(), name) != e.names.end()) return &e;
  return nullptr;
}

}  // namespace

TEST_CASE("completion: options, values, choices and files from the definitions", "[completion]") {
  CLI::App app("test", "gc-test");
  std::string file, out, mode, shape, port, secret;
  double max = 0;
  bool flag = false;
  int verbose = 0;
  app.add_option("FILE", file, "input")->type_name("FILE");
  app.add_option("-o,--output", out, "output")->type_name("FILE");
  app.add_option("--e-mode", mode, "mode")->type_name("MODE")->check(CLI::IsMember({"auto", "relative", "absolute"}));
  app.add_option("--shape", shape, "shape")->type_name("flat|cylinder");
  app.add_option("--port", port, "port")->type_name("PATH|virtual[:OPTS]");
  app.add_option("--max", max, "max")->type_name("MM");
  app.add_flag("--travel", flag, "flag");
  app.add_flag("-v,--verbose", verbose, "repeatable flag");
  app.add_option("--secret", secret, "hidden")->group("");
  std::vector<CompletionEntry> all = gcode::cli::completion_entries(app);

  CHECK(entry(all, "--secret") == nullptr);
  const CompletionEntry* o = entry(all, "-o");
  REQUIRE(o != nullptr);
  CHECK(o->names == std::vector<std::string>{"-o", "--output"});
  CHECK(o->takes_value);
  CHECK(o->file_value);
  const CompletionEntry* e = entry(all, "--e-mode");
  REQUIRE(e != nullptr);
  CHECK(e->choices == std::vector<std::string>{"auto", "relative", "absolute"});
  CHECK_FALSE(e->file_value);
  CHECK(entry(all, "--shape")->choices == std::vector<std::string>{"flat", "cylinder"});
  // A path, or the word "virtual" (its options after it are not completed).
  CHECK(entry(all, "--port")->choices == std::vector<std::string>{"virtual"});
  CHECK(entry(all, "--port")->file_value);
  CHECK(entry(all, "--max")->choices.empty());
  CHECK(entry(all, "--max")->takes_value);
  CHECK_FALSE(entry(all, "--max")->file_value);
  CHECK_FALSE(entry(all, "--travel")->takes_value);
  CHECK_FALSE(entry(all, "--verbose")->takes_value);
  CHECK(entry(all, "--help") != nullptr);  // CLI11's own

  std::string script = gcode::cli::bash_completion("gc-test", all);
  CHECK(script.find("complete -o filenames -F _gc_test gc-test\n") != std::string::npos);
  CHECK(script.find("    --e-mode)\n        COMPREPLY=($(compgen -W 'auto relative absolute' -- \"$cur\")); return 0 ;;") !=
        std::string::npos);
  CHECK(script.find("-o|--output)\n        COMPREPLY=($(compgen -f") != std::string::npos);
  CHECK(script.find("--port)\n        COMPREPLY=($(compgen -W 'virtual' -- \"$cur\") $(compgen -f -- \"$cur\")); return 0 ;;") !=
        std::string::npos);
  CHECK(script.find("--max)\n        return 0 ;;") != std::string::npos);
  CHECK(script.find("--secret") == std::string::npos);
  // FILE: file names where no option is being completed.
  CHECK(script.find("  fi\n  COMPREPLY=($(compgen -f -- \"$cur\"))\n}") != std::string::npos);
}
