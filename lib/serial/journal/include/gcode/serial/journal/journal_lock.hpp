#pragma once
// One gc-send per journal: two writing the same journal (a second print
// started on the same port, a --resume while the first still runs) would
// interleave their records and send the printer two streams. The lock is
// flock() on a file beside the journal (J.lock), not on the journal itself,
// which is replaced by rename() at every compaction. flock() ends with the
// process, so a gc-send killed with SIGKILL leaves nothing to clear; the
// file keeps the holder's pid only to name it in the refusal.
#include <string>

namespace gcode::serial {

class JournalLock {
 public:
  // Takes the lock of `journal_path` for as long as the object lives;
  // throws JournalError (naming the holder's pid when known) when another
  // process holds it, or when the lock file cannot be made.
  explicit JournalLock(const std::string& journal_path);
  ~JournalLock();
  JournalLock(const JournalLock&) = delete;
  JournalLock& operator=(const JournalLock&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace gcode::serial
