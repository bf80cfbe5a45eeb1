// Messages in the gc tools' form (core/diagnostics.hpp): "gc-NAME: line N:
// warning: ...", warnings counted and cut after the limit with one closing
// count, -q silencing all but errors, -v adding information.
#include <catch2/catch.hpp>

#include <string>
#include <string_view>

#include "gcode/core/diagnostics.hpp"
#include "capture.hpp"

using gcode::Diagnostics;

using gctest::stderr_of;

TEST_CASE("diagnostics: warnings with and without a line, errors and information", "[diagnostics]") {
  std::string err = stderr_of([] {
    Diagnostics d("gc-test");
    d.warn(12, "bad number");
    d.warn("no bed size");
    d.error("cannot open x");
    d.info("hidden at verbosity 0");
    CHECK(d.warnings() == 2);
    CHECK(d.tool() == "gc-test");
  });
  CHECK(err ==
        "gc-test: line 12: warning: bad number\n"
        "gc-test: warning: no bed size\n"
        "gc-test: cannot open x\n");
}

TEST_CASE("diagnostics: after the limit only the count is reported", "[diagnostics]") {
  std::string err = stderr_of([] {
    Diagnostics d("gc-test", 0, 2);
    for (int i = 1; i <= 5; ++i) d.warn(static_cast<std::uint64_t>(i), "junk");
    CHECK(d.warnings() == 5);
  });
  CHECK(err ==
        "gc-test: line 1: warning: junk\n"
        "gc-test: line 2: warning: junk\n"
        "gc-test: 3 more warnings not shown\n");
  // Exactly at the limit: no closing count.
  std::string at = stderr_of([] {
    Diagnostics d("gc-test", 0, 2);
    d.warn("a");
    d.warn("b");
  });
  CHECK(at == "gc-test: warning: a\ngc-test: warning: b\n");
}

TEST_CASE("diagnostics: quiet keeps errors only, verbose adds information", "[diagnostics]") {
  std::string quiet = stderr_of([] {
    Diagnostics d("gc-test", -1, 1);
    d.warn(1, "a");
    d.warn(2, "b");
    d.info("i");
    d.error("e");
    CHECK(d.warnings() == 2);  // still counted
  });
  CHECK(quiet == "gc-test: e\n");
  std::string verbose = stderr_of([] {
    Diagnostics d("gc-test");
    d.set_verbosity(1);
    CHECK(d.verbosity() == 1);
    d.info("pause before layer 3");
    d.warn(4, "w");
  });
  CHECK(verbose == "gc-test: pause before layer 3\ngc-test: line 4: warning: w\n");
}

TEST_CASE("diagnostics: a report is printed even when quiet, and ends at a NUL byte", "[diagnostics]") {
  using namespace std::string_view_literals;
  std::string err = stderr_of([] {
    Diagnostics d("gc-test", -1);
    d.report("summary: lines 12");
    d.report("<- ok T:21\0noise"sv);
  });
  CHECK(err == "gc-test: summary: lines 12\ngc-test: <- ok T:21\n");
}
