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

 private:
  int fd_ = 1;
  bool owned_ = false;
  std::string temp_;
  std::string target_;
};

}  // namespace gcode
