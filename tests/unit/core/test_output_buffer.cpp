// Buffered output (core/output_buffer.hpp): bytes come out in order whatever
// the mix of small writes, put() and writes larger than the buffer; a closed
// pipe is BrokenPipe (not a signal), other write errors are system errors,
// and the destructor flushes without throwing.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <string>
#include <system_error>

#include "gcode/core/output_buffer.hpp"
#include "test_support.hpp"

using gcode::OutputBuffer;

TEST_CASE("output buffer: small writes, put and large writes keep their order", "[output_buffer]") {
  std::string target;
  std::string expected;
  {
    OutputBuffer out(target, 8);
    out.write("G1 X");      // 4 of 8
    out.put('1');           // 5
    out.write("\nG1");      // 8: exactly full, still buffered
    CHECK(target.empty());
    CHECK(out.bytes_written() == 8);
    out.put(' ');           // full: flushes first
    CHECK(target == "G1 X1\nG1");
    out.write("Y123456789\n");  // larger than the buffer: flushed, then written at once
    CHECK(target == "G1 X1\nG1 Y123456789\n");
    out.write("abcdefg");   // fits after a flush
    out.write("hi");        // does not fit: flush, then buffered
    CHECK(target == "G1 X1\nG1 Y123456789\nabcdefg");
    out.write("");
    CHECK(out.bytes_written() == 29);
    expected = "G1 X1\nG1 Y123456789\nabcdefghi";
  }
  CHECK(target == expected);  // the destructor flushed the rest
}

TEST_CASE("output buffer: every byte reaches a file descriptor", "[output_buffer]") {
  std::string path = gctest::temp_dir() + "/out";
  std::string expected;
  {
    int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    REQUIRE(fd >= 0);
    {
      OutputBuffer out(fd, 64);
      for (int i = 0; i < 1000; ++i) {
        std::string line = "G1 X" + std::to_string(i) + " E" + std::to_string(i * 7) + "\n";
        out.write(line);
        expected += line;
        if (i % 3 == 0) {
          out.put(';');
          expected += ';';
        }
      }
      out.flush();
      CHECK(out.bytes_written() == expected.size());
    }
    ::close(fd);
  }
  CHECK(gctest::read_file(path) == expected);
}

TEST_CASE("output buffer: a closed pipe throws BrokenPipe, not SIGPIPE", "[output_buffer]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  ::close(fds[0]);
  {
    OutputBuffer out(fds[1], 16);
    out.write("G28\n");  // buffered: nothing noticed yet
    CHECK_THROWS_AS(out.flush(), gcode::BrokenPipe);
    out.write("more\n");
  }  // the destructor's failed flush is swallowed
  ::close(fds[1]);
}

TEST_CASE("output buffer: other write errors name the call", "[output_buffer]") {
  int fd = ::open("/dev/full", O_WRONLY);
  if (fd < 0) return;  // no /dev/full here
  OutputBuffer out(fd, 16);
  out.write("G1 X1\n");
  try {
    out.flush();
    FAIL("no error on /dev/full");
  } catch (const std::system_error& e) {
    CHECK(e.code().value() == ENOSPC);
    CHECK(std::string(e.what()).rfind("write", 0) == 0);
  }
  ::close(fd);
}
