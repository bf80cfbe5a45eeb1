// Both ends of a regular file (core/file_ends.hpp): whole lines at the head,
// the exact last bytes at the tail, the whole file once when it is small,
// the offset untouched, and no answer for a pipe.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <string>

#include "gcode/core/file_ends.hpp"
#include "test_support.hpp"

using gcode::FileEnds;
using gcode::read_file_ends;

namespace {

std::string file_with(const std::string& text) {
  std::string path = gctest::temp_dir() + "/f.gcode";
  gctest::write_file(path, text);
  return path;
}

}  // namespace

TEST_CASE("file ends: a small file is read whole into the head", "[file_ends]") {
  gctest::OpenedFile f(file_with("G28\nG1 X1\nno newline"));
  FileEnds ends;
  ends.tail = "stale";
  REQUIRE(read_file_ends(f.fd(), 16, 8, ends));
  CHECK(ends.head == "G28\nG1 X1\nno newline");  // 21 bytes <= 16 + 8: nothing cut
  CHECK(ends.tail.empty());
}

TEST_CASE("file ends: the head ends after its last whole line, the tail is the last bytes", "[file_ends]") {
  std::string text = "; head line one\n; head line two\nG1 X1 E1\nG1 X2 E2\nG1 X3 E3\n; use_relative_e_distances = 1\n";
  gctest::OpenedFile f(file_with(text));
  REQUIRE(::lseek(f.fd(), 7, SEEK_SET) == 7);
  FileEnds ends;
  REQUIRE(read_file_ends(f.fd(), 20, 10, ends));
  CHECK(ends.head == "; head line one\n");       // 20 bytes cut back to the line end at 16
  CHECK(ends.tail == text.substr(text.size() - 10));
  CHECK(ends.tail == "ances = 1\n");
  CHECK(::lseek(f.fd(), 0, SEEK_CUR) == 7);       // pread: the offset stays
}

TEST_CASE("file ends: a head without a line end inside it is empty", "[file_ends]") {
  std::string text(100, 'x');
  text += "\nG1 X1\n";
  gctest::OpenedFile f(file_with(text));
  FileEnds ends;
  REQUIRE(read_file_ends(f.fd(), 50, 5, ends));
  CHECK(ends.head.empty());
  CHECK(ends.tail == "1 X1\n");
}

TEST_CASE("file ends: an empty file has two empty ends", "[file_ends]") {
  gctest::OpenedFile f(file_with(""));
  FileEnds ends;
  REQUIRE(read_file_ends(f.fd(), 64, 64, ends));
  CHECK(ends.head.empty());
  CHECK(ends.tail.empty());
}

TEST_CASE("file ends: a pipe is not a regular file", "[file_ends]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  REQUIRE(::write(fds[1], "G1 X1\n", 6) == 6);
  FileEnds ends;
  CHECK_FALSE(read_file_ends(fds[0], 64, 64, ends));
  char b[8];
  CHECK(::read(fds[0], b, sizeof b) == 6);  // nothing was consumed
  ::close(fds[0]);
  ::close(fds[1]);
}
