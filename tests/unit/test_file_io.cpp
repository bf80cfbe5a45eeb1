// FILE, '-', -o and -i (core/file_io.hpp): readable messages for what cannot be
// opened, a pipe made seekable by spooling it, an in-place temp file beside
// FILE that replaces it only on commit (with FILE's permissions) and is
// removed otherwise.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "gcode/core/file_io.hpp"
#include "capture.hpp"

using gcode::InputFile;
using gcode::OutputFile;

namespace {

std::string read_all(int fd) {
  std::string out;
  char b[7];
  for (ssize_t n; (n = ::read(fd, b, sizeof b)) > 0;) out.append(b, static_cast<std::size_t>(n));
  return out;
}

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST_CASE("io: FILE, '-' and nothing", "[io]") {
  CHECK(InputFile("").fd() == 0);
  CHECK(InputFile("-").fd() == 0);
  CHECK(InputFile("-").name() == "<stdin>");
  std::string path = gctest::temp_dir() + "/in.gcode";
  gctest::write_file(path, "G28\n");
  InputFile in(path);
  CHECK(in.fd() > 2);
  CHECK(in.name() == path);
  CHECK(read_all(in.fd()) == "G28\n");
  in.rewind();
  CHECK(read_all(in.fd()) == "G28\n");
}

TEST_CASE("io: what cannot be read is a readable error", "[io]") {
  std::string dir = gctest::temp_dir();
  CHECK_THROWS_WITH(InputFile(dir + "/missing.gcode"), dir + "/missing.gcode: No such file or directory");
  CHECK_THROWS_WITH(InputFile(dir), dir + ": is a directory");
  CHECK_THROWS_WITH(OutputFile(dir + "/no/such/dir.gcode", ""), dir + "/no/such/dir.gcode: No such file or directory");
}

TEST_CASE("io: a pipe is spooled to a temp file to be read twice", "[io]") {
  std::string text;
  for (int i = 0; i < 20000; ++i) text += "G1 X" + std::to_string(i) + "\n";  // more than one 256 KB block
  gctest::with_piped_stdin(text, [&] {
    InputFile in("-");
    CHECK(::lseek(in.fd(), 0, SEEK_CUR) < 0);
    in.make_seekable();
    CHECK(in.fd() != 0);
    CHECK(read_all(in.fd()) == text);
    in.rewind();
    CHECK(read_all(in.fd()) == text);
    in.make_seekable();  // already seekable: nothing to do
    in.rewind();
    CHECK(read_all(in.fd()) == text);
  });
  // A regular file stays what it is.
  std::string path = gctest::temp_dir() + "/in.gcode";
  gctest::write_file(path, "G28\n");
  InputFile file(path);
  int fd = file.fd();
  file.make_seekable();
  CHECK(file.fd() == fd);
}

TEST_CASE("io: -o creates or truncates the file", "[io]") {
  std::string path = gctest::temp_dir() + "/out.gcode";
  gctest::write_file(path, "old and longer content\n");
  {
    OutputFile out(path, "");
    REQUIRE(::write(out.fd(), "G28\n", 4) == 4);
    out.commit();
    out.commit();  // once is enough
  }
  CHECK(gctest::read_file(path) == "G28\n");
  CHECK(OutputFile("", "").fd() == 1);
  CHECK(OutputFile("-", "").fd() == 1);
}

TEST_CASE("io: -i replaces FILE on commit only, keeping its permissions", "[io]") {
  std::string dir = gctest::temp_dir();
  std::string path = dir + "/print.gcode";
  gctest::write_file(path, "original\n");
  REQUIRE(::chmod(path.c_str(), 0640) == 0);
  {
    OutputFile out("", path);
    REQUIRE(::write(out.fd(), "half", 4) == 4);
    CHECK(files_in(dir) == 2);  // the temp file sits beside FILE
    // no commit: a failure
  }
  CHECK(gctest::read_file(path) == "original\n");
  CHECK(files_in(dir) == 1);  // the temp file is gone
  {
    OutputFile out("", path);
    REQUIRE(::write(out.fd(), "rewritten\n", 10) == 10);
    CHECK(gctest::read_file(path) == "original\n");  // not before the commit
    out.commit();
  }
  CHECK(gctest::read_file(path) == "rewritten\n");
  CHECK(files_in(dir) == 1);
  struct stat st {};
  REQUIRE(::stat(path.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0640);
}
