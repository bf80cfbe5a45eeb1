#pragma once
// gc-send's control channel: a named pipe (FIFO) that anyone allowed to
// write to it can send commands through while a print runs:
//
//   echo pause > $XDG_RUNTIME_DIR/gc-send/ttyACM0.fifo
//
// The FIFO controls a machine with a hot nozzle, so it is checked before use:
// created 0600 when missing (its folder 0700), refused when the path is not a
// FIFO, belongs to another user, or can be written by group or others.
//
// It must never block the print: it is opened O_RDWR | O_NONBLOCK (Linux),
// so the reading end always has a writer (itself) and never sees end of
// file when a writer closes, and an open() by a writer never waits either.
// A writer that opens and never writes, half a line, or a megabyte of junk
// cost nothing but a message: the parser buffers partial lines up to
// kMaxLine bytes, drops what is longer or not text, and says so once.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/serial/control/control_verbs.hpp"  // ControlCommand

namespace gcode::serial {

// Splits the bytes written into the FIFO into command lines.
class ControlParser {
 public:
  static constexpr std::size_t kMaxLine = 1024;

  using Handler = std::function<void(const ControlCommand&)>;
  // `junk` is called once per run of bad input (over-long or binary lines),
  // with a description, and again only after a good line came in between.
  using JunkHandler = std::function<void(std::string_view why)>;
  ControlParser(Handler on_command, JunkHandler on_junk);

  void feed(std::string_view bytes);
  std::uint64_t commands() const { return commands_; }
  std::uint64_t junk_bytes() const { return junk_bytes_; }

 private:
  void line_done();
  void junk(std::string_view why);

  Handler on_command_;
  JunkHandler on_junk_;
  std::string line_;
  bool skipping_ = false;   // inside an over-long or binary line: dropped to its newline
  bool reported_ = false;   // bad input reported since the last good line
  std::uint64_t commands_ = 0;
  std::uint64_t junk_bytes_ = 0;
};

// The default path: $XDG_RUNTIME_DIR/gc-send/<port>.fifo, else
// /tmp/gc-send-<uid>/<port>.fifo; <port> is the port's file name
// ("ttyACM0", "virtual").
std::string default_control_path(std::string_view port);

// Why `path` may not be used as a control FIFO by user `uid` ("" when it
// may): not a FIFO, another owner, writable by group or others. For tests
// and for ControlFifo.
std::string control_path_problem(const std::string& path, unsigned uid);

class ControlFifo {
 public:
  // Creates the FIFO (mode 0600; a missing folder 0700) or checks the one
  // there, and opens it without blocking. Throws std::runtime_error with a
  // readable message when it is refused.
  explicit ControlFifo(std::string path);
  ~ControlFifo();  // closes; removes the FIFO if it made it
  ControlFifo(const ControlFifo&) = delete;
  ControlFifo& operator=(const ControlFifo&) = delete;

  int fd() const { return fd_; }
  const std::string& path() const { return path_; }
  // Reads what is there (never blocks) into `parser`.
  void read_into(ControlParser& parser);

 private:
  std::string path_;
  int fd_ = -1;
  bool created_ = false;
};

}  // namespace gcode::serial
