// What a print's input was (gcode/serial/journal/input_identity.hpp): a
// regular file by size and time, any input by the hash of its bytes so far,
// the same however the bytes were cut into pieces.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <string>

#include "gcode/serial/journal/input_identity.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("input identity: a regular file by its size, a pipe as a stream", "[serial][input_identity]") {
  const std::string file = gctest::temp_dir() + "/identity.gcode";
  gctest::write_file(file, "G1 X1\nG1 X2\n");
  int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  REQUIRE(fd >= 0);
  InputIdentity id = identify_input(file, fd);
  ::close(fd);
  CHECK(id.path == file);
  CHECK(id.regular);
  CHECK(id.size == 12);
  CHECK(id.mtime_ns > 0);
  int pipe_fds[2];
  REQUIRE(::pipe(pipe_fds) == 0);
  InputIdentity stream = identify_input("-", pipe_fds[0]);
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
  CHECK(stream.path == "-");
  CHECK_FALSE(stream.regular);
}

TEST_CASE("input identity: the prefix hash is the same however the bytes come", "[serial][input_identity]") {
  PrefixHash whole;
  whole.update("G1 X1\nG1 X2\n");
  PrefixHash pieces;
  pieces.update("G1 X");
  pieces.update("1\nG1 X2\n");
  CHECK(pieces.digest() == whole.digest());
  CHECK(pieces.bytes() == 12);
  PrefixHash on;
  on.copy_from(pieces);
  on.update("G1 X3\n");
  CHECK(on.digest() != whole.digest());
  CHECK(pieces.digest() == whole.digest());  // copy_from left it as it was
  const std::string text = hash_text(whole.digest());
  CHECK(text.size() == 16);
  CHECK(text.find_first_not_of("0123456789abcdef") == std::string::npos);
}
