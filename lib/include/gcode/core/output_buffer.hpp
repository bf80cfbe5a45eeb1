#pragma once
// Large buffered writes to a file descriptor.
//
// A closed pipe (`gc-layers big.gcode | head`) is not an error worth a
// message: write() reports EPIPE and OutputBuffer throws BrokenPipe, which a
// tool's main turns into a quiet exit.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gcode {

struct BrokenPipe : std::runtime_error {
  BrokenPipe() : std::runtime_error("broken pipe") {}
};

class OutputBuffer {
 public:
  explicit OutputBuffer(int fd, std::size_t capacity = 1 << 18);
  // Collects into a string instead (tests, text a tool builds in memory).
  explicit OutputBuffer(std::string& target, std::size_t capacity = 1 << 16);
  ~OutputBuffer();  // flushes; errors in the destructor are swallowed
  OutputBuffer(const OutputBuffer&) = delete;
  OutputBuffer& operator=(const OutputBuffer&) = delete;

  void write(std::string_view bytes) {
    if (bytes.size() <= capacity_ - used_) {
      std::char_traits<char>::copy(data_.data() + used_, bytes.data(), bytes.size());
      used_ += bytes.size();
    } else {
      write_slow(bytes);
    }
  }
  void put(char c) {
    if (used_ == capacity_) flush();
    data_[used_++] = c;
  }
  void flush();
  std::size_t bytes_written() const { return total_ + used_; }

 private:
  void write_slow(std::string_view bytes);
  void write_all(const char* p, std::size_t n);

  int fd_;
  std::string* target_ = nullptr;
  std::size_t capacity_;
  std::vector<char> data_;
  std::size_t used_ = 0;
  std::size_t total_ = 0;
};

}  // namespace gcode
