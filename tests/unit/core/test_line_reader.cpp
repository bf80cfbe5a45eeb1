#include <catch2/catch.hpp>

#include <unistd.h>

#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "gcode/core/line_reader.hpp"
#include "gcode/core/output_buffer.hpp"
#include "test_support.hpp"

namespace {

// Reads `data` through a pipe with a small block size, so lines straddle reads.
std::string roundtrip(const std::string& data, std::size_t block, std::size_t* count = nullptr) {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  std::thread writer([&] {
    std::size_t done = 0;
    while (done < data.size()) {
      ssize_t n = ::write(fds[1], data.data() + done, std::min<std::size_t>(data.size() - done, 70000));
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    ::close(fds[1]);
  });
  gcode::LineReader reader(fds[0], block);
  std::string out;
  gcode::RawLine line;
  std::size_t n = 0;
  std::uint64_t expected_offset = 0;
  while (reader.next(line)) {
    CHECK(line.offset == expected_offset);
    expected_offset += line.size();
    out.append(line.text);
    out.append(line.ending);
    ++n;
  }
  writer.join();
  ::close(fds[0]);
  if (count) *count = n;
  return out;
}

}  // namespace

TEST_CASE("endings are kept exactly: LF, CRLF, none at the end", "[line_reader]") {
  std::string data = "G1 X1\r\nG1 X2\nG1 X3\r\n;last";
  std::size_t n = 0;
  CHECK(roundtrip(data, 4, &n) == data);
  CHECK(n == 4);
  gcode::MemoryLineSplitter split(data);
  gcode::RawLine l;
  REQUIRE(split.next(l));
  CHECK(l.text == "G1 X1");
  CHECK(l.ending == "\r\n");
  REQUIRE(split.next(l));
  CHECK(l.ending == "\n");
  split.next(l);
  REQUIRE(split.next(l));
  CHECK(l.text == ";last");
  CHECK(l.ending.empty());
  CHECK(l.number == 4);
}

TEST_CASE("empty input gives no line, a lone newline gives one empty line", "[line_reader]") {
  std::size_t n = 7;
  CHECK(roundtrip("", 16, &n).empty());
  CHECK(n == 0);
  CHECK(roundtrip("\n", 16, &n) == "\n");
  CHECK(n == 1);
}

TEST_CASE("a 10 MB line comes through whole", "[line_reader]") {
  std::string data = "G1 X1\n" + std::string(10u << 20, 'x') + "\nG1 X2\n";
  std::size_t n = 0;
  CHECK(roundtrip(data, 1 << 16, &n) == data);
  CHECK(n == 3);
}

TEST_CASE("lines of every length near the 16- and 64-byte scan steps split where a plain search does",
          "[line_reader][property]") {
  // The splitter looks for a line's end 16 bytes at a time, then hands long
  // lines to memchr: every length from 0 to 150, each with LF and with CRLF,
  // at every alignment a growing prefix gives.
  std::string data;
  for (std::size_t len = 0; len <= 150; ++len) {
    data.append(std::string(len, static_cast<char>('a' + len % 26))).append("\n");
    data.append(std::string(len, 'r')).append("\r\n");
  }
  data.append("\r");  // a last line that is a lone CR, no newline
  std::vector<std::pair<std::string, std::string>> expected;
  for (std::size_t at = 0; at < data.size();) {
    std::size_t nl = data.find('\n', at);
    if (nl == std::string::npos) {
      expected.emplace_back(data.substr(at), "");
      break;
    }
    std::size_t text_end = nl > at && data[nl - 1] == '\r' ? nl - 1 : nl;
    expected.emplace_back(data.substr(at, text_end - at), data.substr(text_end, nl + 1 - text_end));
    at = nl + 1;
  }
  for (std::size_t block : {16u, 37u, 64u, 1000u, 1u << 18}) {
    gcode::LineSplitter splitter(block);
    splitter.append(data);
    splitter.end_of_input();
    gcode::RawLine line;
    std::size_t i = 0;
    while (splitter.next(line)) {
      REQUIRE(i < expected.size());
      CHECK(line.text == expected[i].first);
      CHECK(line.ending == expected[i].second);
      ++i;
    }
    CHECK(i == expected.size());
    CHECK(roundtrip(data, block) == data);
  }
}

TEST_CASE("binary junk, NUL bytes and invalid UTF-8 pass through", "[line_reader][property]") {
  std::string data;
  for (int i = 0; i < 100000; ++i) data.push_back(static_cast<char>((i * 7919 + i / 13) & 0xff));
  CHECK(roundtrip(data, 1000) == data);
}

TEST_CASE("OutputBuffer writes everything and reports a closed pipe", "[output_buffer]") {
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  ::close(fds[0]);
  gcode::OutputBuffer out(fds[1], 64);
  std::string big(1000, 'a');
  CHECK_THROWS_AS((out.write(big), out.flush()), gcode::BrokenPipe);
  ::close(fds[1]);
}
