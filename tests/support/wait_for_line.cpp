// gctest_wait: the tool tests' scripts wait with it until a file holds a
// line they are waiting for (a journal record, a status file's state). One
// process polls, where a shell loop started a grep, an awk and a sleep
// every few milliseconds: under the sanitizers that polling was a fifth of
// a gc-send test's CPU.
//
//   gctest_wait [--alive PID] [--after REGEX] [--count N] TRIES PAUSE FILE REGEX
//
// Waits until N lines (default 1) of FILE match the basic regular
// expression REGEX (grep's), counting from the first line that matches
// --after on; or PID is gone; or about TRIES x PAUSE seconds passed (twice
// that: the shell loop it replaces also spent time on its processes).
// Exits 0 either way, as that loop did: the test's own checks then say
// what did not happen.
#include <fcntl.h>
#include <regex.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

namespace {

struct Wait {
  long alive = 0;
  std::string after;
  long count = 1;
  long tries = 0;
  double pause = 0;
  std::string file;
  std::string pattern;
};

bool parse(int argc, char** argv, Wait& w) {
  int i = 1;
  for (; i + 1 < argc && argv[i][0] == '-' && argv[i][1] == '-'; i += 2) {
    std::string option = argv[i];
    if (option == "--alive") w.alive = std::atol(argv[i + 1]);
    else if (option == "--after") w.after = argv[i + 1];
    else if (option == "--count") w.count = std::atol(argv[i + 1]);
    else return false;
  }
  if (argc - i != 4) return false;
  w.tries = std::atol(argv[i]);
  w.pause = std::atof(argv[i + 1]);
  w.file = argv[i + 2];
  w.pattern = argv[i + 3];
  return true;
}

class Regex {
 public:
  explicit Regex(const std::string& pattern) : ok_(regcomp(&re_, pattern.c_str(), REG_NOSUB) == 0) {}
  ~Regex() {
    if (ok_) regfree(&re_);
  }
  Regex(const Regex&) = delete;
  Regex& operator=(const Regex&) = delete;
  bool ok() const { return ok_; }
  bool matches(const std::string& line) const { return regexec(&re_, line.c_str(), 0, nullptr, 0) == 0; }

 private:
  regex_t re_{};
  bool ok_;
};

// The file read as it grows: each look reads only the bytes added since
// the last (a journal grows to hundreds of KB while a test waits for its
// last lines), and starts over when the file was replaced (a status file
// is renamed over, a journal compacted) or cut.
class Scan {
 public:
  Scan(const Wait& w, const Regex& pattern, const Regex* after)
      : w_(w), pattern_(pattern), after_(after), counting_(after == nullptr) {}

  // Whether the file holds what is waited for (a missing file does not).
  bool found() {
    int fd = ::open(w_.file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat st{};
    if (::fstat(fd, &st) == 0 && (st.st_ino != inode_ || st.st_size < offset_)) restart(st.st_ino);
    bool done = false;
    char buf[65536];
    ssize_t n;
    while (!done && (n = ::pread(fd, buf, sizeof buf, offset_)) > 0) {
      offset_ += n;
      partial_.append(buf, static_cast<std::size_t>(n));
      done = take_lines();
    }
    ::close(fd);
    return done;
  }

 private:
  void restart(ino_t inode) {
    inode_ = inode;
    offset_ = 0;
    partial_.clear();
    counting_ = after_ == nullptr;
    seen_ = 0;
  }

  // The complete lines read so far; true once what is waited for is there.
  bool take_lines() {
    std::size_t from = 0;
    for (std::size_t nl; (nl = partial_.find('\n', from)) != std::string::npos; from = nl + 1) {
      const std::string line = partial_.substr(from, nl - from);
      if (!counting_ && after_->matches(line)) counting_ = true;
      if (counting_ && w_.count <= 0) return true;  // the --after line is all that is waited for
      if (counting_ && pattern_.matches(line) && ++seen_ >= w_.count) return true;
    }
    partial_.erase(0, from);
    return false;
  }

  const Wait& w_;
  const Regex& pattern_;
  const Regex* after_;
  ino_t inode_ = 0;
  off_t offset_ = 0;
  std::string partial_;
  bool counting_;
  long seen_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  Wait w;
  if (!parse(argc, argv, w)) {
    std::fprintf(stderr, "usage: gctest_wait [--alive PID] [--after REGEX] [--count N] TRIES PAUSE FILE REGEX\n");
    return 2;
  }
  Regex pattern(w.pattern);
  Regex after(w.after.empty() ? "." : w.after);
  if (!pattern.ok() || !after.ok()) {
    std::fprintf(stderr, "gctest_wait: a bad regular expression\n");
    return 2;
  }
  Scan scan(w, pattern, w.after.empty() ? nullptr : &after);
  const auto pause = std::chrono::duration<double>(w.pause);
  const auto deadline = std::chrono::steady_clock::now() + 2 * w.tries * pause;
  while (std::chrono::steady_clock::now() < deadline) {
    if (scan.found()) return 0;
    if (w.alive > 0 && ::kill(static_cast<pid_t>(w.alive), 0) != 0 && errno == ESRCH) return 0;
    std::this_thread::sleep_for(pause);
  }
  return 0;
}
