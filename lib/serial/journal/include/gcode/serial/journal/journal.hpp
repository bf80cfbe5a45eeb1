#pragma once
// gc-send's journal: what it sent to the printer, line by line, so that a
// print can go on after gc-send was killed, the USB link dropped or the
// printer reset (docs/gc-send-journal.md has the whole design).
//
// A file of self-checking text records (journal_record.hpp):
//   H  once, first: the input's identity, the port, the format version;
//   S  a command sent, with every field of the point after it (its protocol
//      line number n, input line and offset, layer, the machine state and
//      what the control changed live);
//   D  the same as a delta: only the fields that changed since the command
//      before (a G1 changes X, Y, E and the input position: ~60 bytes);
//   A  the newest line the printer acknowledged;
//   F  the print ended normally.
// Each command's record is written before its bytes go to the port, so
// whatever line the printer says it expects next, the journal holds the
// state before it.
//
// Crash consistency: records are appended with write() as they are made
// (a SIGKILL loses nothing written), and fdatasync()ed at every layer and at
// least every `sync_interval` seconds (a power loss loses at most that).
// Reading stops at the first record that does not check: a torn last line
// is a crash's normal trace; a bad record with good ones after it is
// corruption.
//
// Size: once the file passes `compact_bytes`, it is rewritten (temp file,
// fsync, rename) as the header, a snapshot of the oldest command still
// kept, deltas for the `keep` newest (and the `keep` up to the acknowledged
// line, where more were numbered ahead of it) and the acknowledged line:
// bounded on any print, 20 hours or 200.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/serial/journal/journal_record.hpp"

namespace gcode::serial {

// A journal that cannot be used: the message says why (for the user).
class JournalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct JournalOptions {
  std::string path;
  double sync_interval = 1.0;         // seconds at most between fdatasyncs
  std::size_t compact_bytes = 1 << 20;
  std::size_t keep = 256;             // commands kept at a compaction (more than any printer holds)
};

// The default path: <state folder>/<port name>.journal.
std::string default_journal_path(std::string_view port);

struct JournalEntry {
  std::uint64_t n = 0;   // the protocol line number it went out as
  JournalFields point;   // every field after it
};

class JournalWriter {
 public:
  // Creates (0600) or replaces the journal; throws JournalError when its
  // folder can be changed by others, the path is not a regular file of this
  // user, or it cannot be written.
  // `carried`: a resume's commands from the journal it goes on from, oldest
  // first, the last of them the one that ran last (taken as acknowledged).
  // The new file holds them from the moment it replaces the old one: a kill
  // before anything more is written still leaves the print resumable, and a
  // later reset can walk back over the moves the printer held then.
  JournalWriter(JournalOptions options, JournalFields header, std::vector<JournalEntry> carried = {});
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  // A command about to be sent as line `n`, with the point after it. Every
  // point carries the same keys (a key left out counts as unchanged).
  void sent(std::uint64_t n, const JournalFields& point);
  void acknowledged(std::uint64_t n);
  // The next flush also syncs (a layer began, a pause, a fault).
  void sync_soon() { sync_soon_ = true; }
  // Writes what is buffered; syncs when due. Call it before the port's
  // bytes go out, and from a timer (`now` in seconds, any monotonic clock).
  void flush(double now);
  // The print ended normally: F, synced. Nothing more is written.
  void finish(double now);

  // The newest command's full point and the acknowledged line (after a
  // resume's carried commands: the one the print goes on after).
  const JournalFields* last_point() const { return have_last_ ? &last_ : nullptr; }
  std::uint64_t acknowledged_line() const { return acked_; }
  const std::string& path() const { return options_.path; }
  std::uint64_t bytes_written() const { return bytes_total_; }
  std::size_t file_bytes() const { return file_bytes_; }
  int compactions() const { return compactions_; }
  int syncs() const { return syncs_; }

 private:
  void keep(std::uint64_t n, JournalFields changes);
  void trim_kept();
  std::string snapshot() const;
  void write_out(const std::string& text);
  void compact();
  void sync(double now);

  JournalOptions options_;
  JournalFields header_;
  int fd_ = -1;
  std::string buffer_;
  JournalFields last_;              // the full point of the newest command
  bool have_last_ = false;
  // What a compaction keeps, newest last: the oldest as a full point, each
  // after it as its changes since the one before (a copy of every field
  // per command cost more than the rest of the journal).
  std::deque<std::pair<std::uint64_t, JournalFields>> kept_;
  std::uint64_t acked_ = 0;
  bool unsynced_ = false;
  static constexpr std::size_t kMaxKept = 1 << 14;  // points kept at most, acknowledged or not
  bool sync_soon_ = false;
  bool finished_ = false;
  double last_sync_ = -1e300;
  std::size_t file_bytes_ = 0;
  std::uint64_t bytes_total_ = 0;
  int compactions_ = 0;
  int syncs_ = 0;
};

struct JournalContents {
  JournalFields header;
  // Oldest first, numbers rising: a command numbered again replaces those
  // numbered from it on (they were taken back unsent).
  std::vector<JournalEntry> entries;
  std::uint64_t acknowledged = 0;     // 0: none
  bool finished = false;
  bool torn_tail = false;             // the last line was cut short (a crash while writing)
  std::size_t records = 0;

  // The newest entry sent as line n or before it; null when there is none.
  const JournalEntry* at_or_before(std::uint64_t n) const;
};

// Reads a journal back to its last complete record; throws JournalError
// (missing, unreadable, in a folder others may change, no header, another
// format, a bad record followed by good ones).
JournalContents read_journal(const std::string& path);

}  // namespace gcode::serial
