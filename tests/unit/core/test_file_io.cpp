// FILE, '-', -o and -i (core/file_io.hpp): readable messages for what cannot be
// opened, a pipe made seekable by spooling it, an in-place temp file beside
// FILE that replaces it only on commit (with FILE's permissions) and is
// removed otherwise; a pipe widened to 1 MB when asked.
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

TEST_CASE("io: widen_pipe asks for a 1 MB pipe, so the filters of a pipeline run side by side", "[io]") {
  int ends[2];
  REQUIRE(::pipe(ends) == 0);
  REQUIRE(::fcntl(ends[0], F_GETPIPE_SZ) == 65536);  // Linux's default
  {
    InputFile in("/proc/self/fd/" + std::to_string(ends[0]));  // a named pipe or <(...)
    CHECK(::fcntl(ends[0], F_GETPIPE_SZ) == 65536);  // only when asked: gc-send keeps its pipe for a day
    in.widen_pipe();
    CHECK(::fcntl(ends[0], F_GETPIPE_SZ) == 1 << 20);
  }
  int again[2];
  REQUIRE(::pipe(again) == 0);
  {
    OutputFile out("/proc/self/fd/" + std::to_string(again[1]), "");
    out.widen_pipe();
    CHECK(::fcntl(again[1], F_GETPIPE_SZ) == 1 << 20);
  }
  // Standard input and output, as in a pipeline.
  int saved_in = ::dup(0), saved_out = ::dup(1);
  int third[2], fourth[2];
  REQUIRE(::pipe(third) == 0);
  REQUIRE(::pipe(fourth) == 0);
  ::dup2(third[0], 0);
  ::dup2(fourth[1], 1);
  {
    InputFile in("-");
    in.widen_pipe();
    OutputFile out("", "");
    out.widen_pipe();
  }
  const int in_size = ::fcntl(third[0], F_GETPIPE_SZ), out_size = ::fcntl(fourth[1], F_GETPIPE_SZ);
  ::dup2(saved_in, 0);
  ::dup2(saved_out, 1);
  CHECK(in_size == 1 << 20);
  CHECK(out_size == 1 << 20);
  // A file is no pipe: nothing to do, nothing goes wrong.
  std::string path = gctest::temp_dir() + "/plain.gcode";
  gctest::write_file(path, "G28\n");
  InputFile plain(path);
  plain.widen_pipe();
  CHECK(read_all(plain.fd()) == "G28\n");
  for (int fd : {ends[0], ends[1], again[0], again[1], third[0], third[1], fourth[0], fourth[1], saved_in, saved_out})
    ::close(fd);
}
