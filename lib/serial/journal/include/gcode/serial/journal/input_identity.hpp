#pragma once
// What a print's input was, so that a resume can tell it is given the same
// G-code again: a regular file by its size and modification time, and any
// input (a pipeline re-run the same way too: the filters are deterministic)
// by a hash of its bytes up to the point the print reached.
#include <cstdint>
#include <string>
#include <string_view>

struct XXH3_state_s;  // xxhash.h, kept out of this header

namespace gcode::serial {

struct InputIdentity {
  std::string path;           // as given; "-" for standard input
  bool regular = false;       // a regular file (size and mtime mean something)
  std::uint64_t size = 0;
  std::int64_t mtime_ns = 0;
};

// `fd` is the open input (fstat: a pipe has no size); `path` as the user gave it.
InputIdentity identify_input(const std::string& path, int fd);

// The hash of a stream's bytes so far, fed in any pieces (XXH3, 64 bits).
class PrefixHash {
 public:
  PrefixHash();
  ~PrefixHash();
  PrefixHash(const PrefixHash&) = delete;
  PrefixHash& operator=(const PrefixHash&) = delete;

  // Takes over `other`'s state: the hash of a prefix, to hash on past it
  // without changing `other`.
  void copy_from(const PrefixHash& other);
  void update(std::string_view bytes);
  std::uint64_t digest() const;
  std::uint64_t bytes() const { return bytes_; }

 private:
  XXH3_state_s* state_;
  std::uint64_t bytes_ = 0;
};

std::string hash_text(std::uint64_t hash);  // 16 hex digits

}  // namespace gcode::serial
