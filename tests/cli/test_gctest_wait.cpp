// gctest-wait, the tool tests' wait for what a running process writes
// (support/programs/gctest_wait.cpp): the gc-send tests' kill and reset moments
// stand on it.
#include <string>

#include <catch2/catch.hpp>

#include "test_support.hpp"

namespace {

using gctest::quote;

int wait_status(const std::string& options, const std::string& path) {
  return gctest::run(quote(gctest::tool_path("gctest-wait")) + " " + options + " " + quote(path)).status;
}

}  // namespace

TEST_CASE("gctest-wait: a match, a count of lines, a count after a marker, a pattern with a tab", "[wait]") {
  std::string path = gctest::temp_dir() + "/log";
  gctest::write_file(path, "A 1\nrestore=2 x\nA 2\nA 3\n1\t-1\tM114\n2\t7\tG1 X1\nA 4");
  CHECK(wait_status("--match '^A ' --tries 2 --every 0.001", path) == 0);
  CHECK(wait_status("--match 'none' --tries 2 --every 0.001", path) == 1);
  CHECK(wait_status("--at-least 6 --tries 2 --every 0.001", path) == 0);
  // The last line has no newline yet: it is still being written.
  CHECK(wait_status("--at-least 7 --tries 2 --every 0.001", path) == 1);
  CHECK(wait_status("--match '^A ' --after 'restore=[1-9]' --at-least 2 --tries 2 --every 0.001", path) == 0);
  CHECK(wait_status("--match '^A ' --after 'restore=[1-9]' --at-least 3 --tries 2 --every 0.001", path) == 1);
  // With --after, the marker must be there even when no line need follow it.
  CHECK(wait_status("--after 'restore=[1-9]' --at-least 0 --tries 2 --every 0.001", path) == 0);
  CHECK(wait_status("--after 'paused=1' --at-least 0 --tries 2 --every 0.001", path) == 1);
  CHECK(wait_status("--match " + quote("^[^\t]*\t[0-9]") + " --tries 2 --every 0.001", path) == 0);
  CHECK(wait_status("--match " + quote("^[^\t]*\t[0-9]") + " --at-least 2 --tries 2 --every 0.001", path) == 1);
}

TEST_CASE("gctest-wait: a file that grows, one that appears, one renamed over, a process that ends", "[wait]") {
  std::string dir = gctest::temp_dir();
  std::string path = dir + "/status", waiter = quote(gctest::tool_path("gctest-wait"));
  gctest::write_file(path, "{\"state\": \"printing\"}\n");
  auto grown = gctest::run(waiter + " --match '\"paused\"' --tries 500 --every 0.005 " + quote(path) + " & w=$!\n" +
                           "sleep 0.1; printf '{\"state\": \"paused\"}\\n' > " + quote(path + ".tmp") + "; mv " +
                           quote(path + ".tmp") + " " + quote(path) + "\nwait $w");
  CHECK(grown.status == 0);
  // Renamed over: counted again from the start (3 lines, then a file of 2
  // that grows to 4).
  for (int wanted : {4, 5}) {
    gctest::write_file(path, "1\n2\n3\n");
    auto replaced = gctest::run(waiter + " --at-least " + std::to_string(wanted) + " --tries 150 --every 0.01 " +
                                quote(path) + " & w=$!\nsleep 0.1; printf 'a\\nb\\n' > " + quote(path + ".tmp") + "; mv " +
                                quote(path + ".tmp") + " " + quote(path) + "; sleep 0.1; printf 'c\\nd\\n' >> " + quote(path) +
                                "\nwait $w");
    INFO(wanted << " lines");
    CHECK(replaced.status == (wanted == 4 ? 0 : 1));
  }
  auto appears = gctest::run(waiter + " --tries 500 --every 0.005 " + quote(dir + "/later") + " & w=$!\n" +
                             "sleep 0.1; echo x > " + quote(dir + "/later") + "\nwait $w");
  CHECK(appears.status == 0);
  // Gives up once the process it follows is gone, long before its tries.
  auto ended = gctest::run("sleep 0.2 & p=$!\n" + waiter + " --match never --tries 100000 --every 0.01 --while-alive $p " +
                           quote(path) + "; echo $?");
  CHECK(ended.out == "1\n");
  CHECK(gctest::run(waiter + " --tries x " + quote(path)).status == 2);
}
