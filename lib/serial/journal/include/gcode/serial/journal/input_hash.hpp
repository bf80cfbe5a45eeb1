#pragma once
// The hash of a print's input as gc-send feeds it (input_identity.hpp's
// PrefixHash), for the journal's checkpoints: a resume of a re-run pipeline
// checks the bytes up to a checkpoint before its line. A resume hashes the
// part printed before without feeding it, and takes the digest where the
// old journal's checkpoint is, to compare.
#include <cstdint>
#include <string_view>

#include "gcode/serial/journal/input_identity.hpp"

namespace gcode::serial {

class InputHash {
 public:
  // A checkpoint at least this often.
  static constexpr std::uint64_t kCheckpointBytes = 64 * 1024;

  // Bytes fed to the printer. True when a checkpoint is due (the journal
  // is to note bytes() and digest() now).
  bool fed(std::string_view bytes);

  // A resume: `part`, the next bytes the earlier run printed; the digest
  // of the input's first `check_at` bytes is taken on the way.
  void printed(std::string_view part, std::uint64_t check_at);
  // The printed part is hashed, `ahead` read past it (`read_through`: the
  // input held at least `check_at` bytes). A checkpoint a little past the
  // printed part is hashed on into `ahead`, on a copy. The checkpoints
  // count from here.
  void printed_end(std::string_view ahead, std::uint64_t check_at, bool read_through);
  // The digest of the first `check_at` bytes (0 when the input ended before).
  std::uint64_t check_digest() const { return check_; }

  std::uint64_t bytes() const { return hash_.bytes(); }
  std::uint64_t digest() const { return hash_.digest(); }

 private:
  PrefixHash hash_;
  std::uint64_t checkpointed_ = 0;  // bytes at the newest checkpoint
  std::uint64_t check_ = 0;
};

}  // namespace gcode::serial
