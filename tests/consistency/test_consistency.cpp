// The suite behaves as one: checks generated over every tool the build
// defines (CMake's GCODE_TOOLS list, so a tool added on another branch is
// covered the moment it is built), not a list kept by hand.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace {

std::vector<std::string> tools() {
  std::vector<std::string> names;
  std::stringstream list(GC_TOOL_NAMES);
  for (std::string name; std::getline(list, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

// The options --help declares: its lines "  -o,--output FILE  ...", not the
// options its descriptions mention.
std::set<std::string> declared_options(const std::string& help) {
  std::set<std::string> names;
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  -", 0) != 0) continue;
    std::string column = line.substr(2, line.find(' ', 2) - 2);
    std::stringstream parts(column);
    // "--reset,--no-reset{false}": a flag's default value is not its name.
    for (std::string name; std::getline(parts, name, ',');) names.insert(name.substr(0, name.find('{')));
  }
  return names;
}

// The options a man page has an entry for: the tag line after each .TP
// (".BI \-\-max " MM"", ".B \-i, \-\-in\-place"), every name on it.
std::set<std::string> man_entries(const std::string& page) {
  std::set<std::string> names;
  std::istringstream lines(page);
  bool tag = false;
  for (std::string line; std::getline(lines, line);) {
    if (tag && line.rfind(".B", 0) == 0) {
      std::string words = line.substr(line.find(' ') == std::string::npos ? line.size() : line.find(' '));
      // Only the names before the first argument ("MM", "FILE").
      std::string names_part = words.substr(0, words.find('"'));
      for (const std::string& n : gctest::long_options(names_part)) names.insert(n);
    }
    tag = line.rfind(".TP", 0) == 0;
  }
  return names;
}

// Whether a man page names `option` ("\-\-z" in roff), as a whole word:
// long_options leaves out one-letter long names such as --z.
bool names_option(std::string page, const std::string& option) {
  for (std::size_t p; (p = page.find("\\-")) != std::string::npos;) page.erase(p, 1);
  for (std::size_t p = 0; (p = page.find(option, p)) != std::string::npos; p += option.size()) {
    std::size_t end = p + option.size();
    char after = end < page.size() ? page[end] : ' ';
    bool word_ends = !((after >= 'a' && after <= 'z') || (after >= '0' && after <= '9') || after == '-');
    if (word_ends && (p == 0 || page[p - 1] != '-')) return true;
  }
  return false;
}

std::string help_of(const std::string& tool) {
  gctest::RunResult r = gctest::run(gctest::tool_command(tool, "--help"));
  INFO(tool << " --help: " << r.err);
  REQUIRE(r.status == 0);
  return r.out;
}

}  // namespace

TEST_CASE("the build defines tools, each with a man page and a completion", "[consistency]") {
  REQUIRE(tools().size() >= 2);
  for (const std::string& tool : tools()) {
    INFO(tool);
    CHECK(!gctest::read_file(std::string(GC_MAN_DIR) + "/" + tool + ".1").empty());
    std::string completion = gctest::read_file(std::string(GC_COMPLETION_DIR) + "/" + tool);
    CHECK(completion.find("complete -o filenames -F _" ) != std::string::npos);
    CHECK(completion.find(" " + tool + "\n") != std::string::npos);
  }
}

TEST_CASE("every tool prints the CMake project version", "[consistency]") {
  for (const std::string& tool : tools()) {
    gctest::RunResult r = gctest::run(gctest::tool_command(tool, "--version"));
    INFO(tool << ": " << r.err);
    CHECK(r.status == 0);
    CHECK(r.out == tool + " " + GC_PROJECT_VERSION + "\n");
  }
}

TEST_CASE("every tool's --help lists the common options", "[consistency]") {
  for (const std::string& tool : tools()) {
    std::string help = help_of(tool);
    std::set<std::string> options = declared_options(help);
    INFO(tool);
    for (const char* common : {"-h", "--help", "--version", "-q", "--quiet"}) {
      INFO(common);
      CHECK(options.count(common) == 1);
    }
    // A tool that reads G-code ([FILE] or standard input), gc-send too,
    // says more with -v and reads its input as every other: where layers
    // begin (--layer-marker) and the E mode of a file that never says.
    if (help.find(tool + " [OPTIONS] [FILE]") != std::string::npos) {
      for (const char* reading : {"-v", "--verbose", "--layer-marker", "--e-mode"}) {
        INFO(reading);
        CHECK(options.count(reading) == 1);
      }
    }
    CHECK(options.count("--bash-completion") == 0);  // hidden: for the build
    // A filter (it rewrites its FILE in place) takes every filter option.
    if (options.count("--in-place") != 0) {
      for (const char* common : {"-i", "-o", "--output", "--e-mode", "--layer-marker"}) {
        INFO(common);
        CHECK(options.count(common) == 1);
      }
    }
    // A tool that writes G-code to a FILE takes -o like every other.
    if (options.count("-o") != 0) CHECK(options.count("--output") == 1);
  }
}

TEST_CASE("every man page documents every option --help shows", "[consistency]") {
  for (const std::string& tool : tools()) {
    std::string page = gctest::read_file(std::string(GC_MAN_DIR) + "/" + tool + ".1");
    for (const std::string& option : declared_options(help_of(tool))) {
      if (option.rfind("--", 0) != 0) continue;
      INFO(tool << ": man/" << tool << ".1 does not name " << option);
      CHECK(names_option(page, option));
    }
  }
}

TEST_CASE("every option entry of a man page is an option of the tool", "[consistency]") {
  for (const std::string& tool : tools()) {
    std::set<std::string> options = declared_options(help_of(tool));
    std::set<std::string> entries = man_entries(gctest::read_file(std::string(GC_MAN_DIR) + "/" + tool + ".1"));
    INFO(tool);
    CHECK(entries.size() >= 3);  // the page has an OPTIONS section this test reads
    for (const std::string& entry : entries) {
      INFO(tool << ": man/" << tool << ".1 has an entry for " << entry << ", which --help does not show");
      CHECK(options.count(entry) == 1);
    }
  }
}

TEST_CASE("every tool answers a usage error alike: exit 2, its name, a pointer to --help", "[consistency]") {
  for (const std::string& tool : tools()) {
    gctest::RunResult r = gctest::run(gctest::tool_command(tool, "--no-such-option"));
    INFO(tool << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.rfind(tool + ": ", 0) == 0);
    CHECK(r.err.find("(see " + tool + " --help)") != std::string::npos);
    CHECK(r.out.empty());
  }
}

TEST_CASE("README's table of tools has a row for every tool, linking its man page", "[consistency]") {
  std::string readme = gctest::read_file(GC_README);
  for (const std::string& tool : tools()) {
    INFO("README.md lacks the row \"| [" << tool << "](man/" << tool << ".1) | ... |\"");
    CHECK(readme.find("\n| [" + tool + "](man/" + tool + ".1) | ") != std::string::npos);
  }
}
