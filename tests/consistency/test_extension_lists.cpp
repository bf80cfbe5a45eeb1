// One list per extension point, and the pages that name its entries agree
// with it: gc-send's control verbs (gcode/serial/control_verbs.hpp) in
// --help and the man page's CONTROL section, exactly and in order; the
// firmwares (gcode/core/firmware.hpp, firmwares()) in the man pages of
// gc-send and gc-virtual-printer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "gcode/core/firmware.hpp"
#include "gcode/serial/control/control_verbs.hpp"
#include "test_support.hpp"

namespace test_extension_lists {

// "speed F" from a tag line `.BI "speed " F` (quotes and roff's macro
// dropped, blanks collapsed).
std::string tag_text(const std::string& line) {
  std::string text;
  for (char c : line.substr(line.find(' ') + 1)) {
    if (c == '"') continue;
    if (c == ' ' && (text.empty() || text.back() == ' ')) continue;
    text += c;
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// The entries of a man page's section (".SH CONTROL"): the tag lines after
// .TP, options (\-\-control) left out.
std::vector<std::string> entries(const std::string& page, const std::string& section) {
  std::vector<std::string> found;
  std::istringstream lines(page);
  bool in_section = false, tag = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(".SH", 0) == 0) in_section = line == section;
    if (in_section && tag && line.rfind(".B", 0) == 0 && line.find("\\-") == std::string::npos)
      found.push_back(tag_text(line));
    tag = line.rfind(".TP", 0) == 0;
  }
  return found;
}

// The text of a man page's section, up to the next .SH.
std::string section_of(const std::string& page, const std::string& section) {
  std::size_t at = page.find("\n" + section + "\n");
  if (at == std::string::npos) return std::string();
  std::size_t end = page.find("\n.SH", at + 1);
  return page.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

// Whether `text` holds `word` with no letter or digit on either side.
bool names_word(const std::string& text, std::string_view word) {
  auto alnum = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); };
  for (std::size_t p = 0; (p = text.find(word, p)) != std::string::npos; ++p) {
    std::size_t end = p + word.size();
    if ((p == 0 || !alnum(text[p - 1])) && (end >= text.size() || !alnum(text[end]))) return true;
  }
  return false;
}

std::string man_page(const std::string& tool) { return gctest::read_file(std::string(GC_MAN_DIR) + "/" + tool + ".1"); }

std::vector<std::string> table_usages() {
  std::vector<std::string> usages;
  for (const gcode::serial::ControlVerb& v : gcode::serial::control_verbs()) usages.push_back(v.usage());
  return usages;
}

}  // namespace test_extension_lists

TEST_CASE("gc-send control: man page lists each verb of the table, in its order", "[consistency][control]") {
  using namespace test_extension_lists;
  CHECK(entries(man_page("gc-send"), ".SH CONTROL") == table_usages());
}

TEST_CASE("gc-send control: --help shows each verb of the table with its help", "[consistency][control]") {
  gctest::RunResult r = gctest::run(gctest::tool_command("gc-send", "--help"));
  REQUIRE(r.status == 0);
  for (const gcode::serial::ControlVerb& v : gcode::serial::control_verbs()) {
    std::string line = fmt::format("\n  {:<12} {}\n", v.usage(), v.help);
    INFO("gc-send --help lacks the line" << line);
    CHECK(r.out.find(line) != std::string::npos);
  }
}

TEST_CASE("firmwares: gc-virtual-printer's man page has an entry for each of the list", "[consistency][firmware]") {
  using namespace test_extension_lists;
  std::vector<std::string> tags = entries(man_page("gc-virtual-printer"), ".SH FIRMWARE FLAVOURS");
  for (const gcode::FirmwareFlavor* f : gcode::firmwares()) {
    std::string tag(f->name);
    if (!f->also_named.empty()) tag += fmt::format(" ({})", f->also_named);
    INFO("man/gc-virtual-printer.1's FIRMWARE FLAVOURS lacks the entry " << tag);
    CHECK(std::find(tags.begin(), tags.end(), tag) != tags.end());
  }
  CHECK(tags.size() == gcode::firmwares().size());
}

TEST_CASE("firmwares: gc-send's man page and gc-virtual-printer --help name each of the list",
          "[consistency][firmware]") {
  using namespace test_extension_lists;
  std::string section = section_of(man_page("gc-send"), ".SH FIRMWARE FLAVOURS");
  for (const gcode::FirmwareFlavor* f : gcode::firmwares()) {
    INFO("man/gc-send.1's FIRMWARE FLAVOURS does not name the firmware " << f->name);
    CHECK(names_word(section, f->name));
  }
  gctest::RunResult r = gctest::run(gctest::tool_command("gc-virtual-printer", "--help"));
  REQUIRE(r.status == 0);
  for (const gcode::FirmwareFlavor* f : gcode::firmwares()) CHECK(names_word(r.out, f->name));
}
