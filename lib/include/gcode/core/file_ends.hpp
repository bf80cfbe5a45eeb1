#pragma once
// The two ends of a regular file, read without moving its offset: what a
// tool needs to know before streaming sits at the start (Cura's header) or
// at the end (PrusaSlicer's config block).
#include <cstddef>
#include <string>

namespace gcode {

struct FileEnds {
  std::string head;  // up to `head_bytes`, cut after its last whole line
  std::string tail;  // the last `tail_bytes` (empty when the head holds the whole file)
};

// False when `fd` is not a regular file (a pipe: the caller reads ahead instead).
bool read_file_ends(int fd, std::size_t head_bytes, std::size_t tail_bytes, FileEnds& ends);

}  // namespace gcode
