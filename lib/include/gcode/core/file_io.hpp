#pragma once
// Opening a program's input and output by the conventions every gc tool
// shares: FILE or '-' for stdin, -o FILE, and -i/--in-place (write a temp
// file beside FILE, rename it over FILE only when the program succeeded, as
// slicer post-processing hooks need). Plain files and descriptors: nothing
// here knows about command lines.
#include <string>

namespace gcode {

class InputFile {
 public:
  // "" or "-" is stdin. Throws std::runtime_error with a readable message.
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  int fd() const { return fd_; }
  const std::string& name() const { return name_; }
  // For tools that must read the input twice (e.g. "the last 3 layers"):
  // a pipe is copied to an unlinked temp file first. Then rewinds.
  void make_seekable();
  void rewind();
  // A pipe between two filters holds 64 KB by default: the writer blocks
  // after a quarter of one of its 256 KB writes and the reader wakes for
  // every piece, so the tools of a pipeline take turns instead of running
  // side by side. This asks for 1 MB, what Linux lets any user ask for
  // (pipe-max-size); where it refuses, the pipe stays as it was. Only for
  // the filters, which end with their input: the pages count against the
  // user's pipe quota (pipe-user-pages-soft) while the pipe lives, and a
  // sender printing for a day keeps its pipe that long.
  // `gc-pause-at | gc-subdivide | gc-speedup` on the bench's 160 MB file:
  // 1.34-1.47 s -> 1.01-1.12 s of wall time, the same CPU.
  void widen_pipe();

 private:
  int fd_ = 0;
  bool owned_ = false;
  std::string name_;
};

class OutputFile {
 public:
  // Exactly one of: `path` empty or "-" (stdout), a path (-o), or
  // `in_place_of` (-i): a temp file in the same folder, renamed on commit().
  OutputFile(const std::string& path, const std::string& in_place_of);
  ~OutputFile();  // an uncommitted temp file is removed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  int fd() const { return fd_; }
  // Finishes the output: closes a file and renames an in-place temp over its target.
  void commit();
  // As InputFile::widen_pipe, for the pipe this writes to.
  void widen_pipe();

 private:
  int fd_ = 1;
  bool owned_ = false;
  std::string temp_;
  std::string target_;
};

}  // namespace gcode
