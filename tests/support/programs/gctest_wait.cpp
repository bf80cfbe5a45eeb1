// gctest-wait: the tool tests' way to wait for what a running process
// writes (gc-send's status file and journal, the virtual printer's log).
//
//   gctest-wait [--match RE] [--after RE] [--at-least N] [--tries N]
//               [--every SECONDS] [--while-alive PID] FILE
//
// Waits until FILE has N complete lines (default 1) matching RE (a basic
// regular expression, as grep's; default: any line). With --after, the
// count starts at the first line matching its RE (that line included, as
// awk's '/after/{r=1} r && /match/'), and that line must be there, even
// for N = 0. It looks up to --tries times (default
// 1000), --every seconds apart (default 0.01), and stops early once process
// PID is gone. Exit 0 when it saw what it waited for, 1 when it gave up
// (the test's own checks then say what did not happen), 2 on a usage error.
//
// Why not a shell loop: a `grep` and a `sleep` started every few
// milliseconds cost about 8 ms of CPU a turn on the test machine, so a loop
// waiting 2 ms apart kept a core busy for as long as it waited, beside the
// processes under test. This program reads only what was appended since
// its last look.
#include <fcntl.h>
#include <regex.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <string_view>

namespace {

// What has been read of a file that grows by appends and may be replaced
// whole (a rename over it, as gc-send writes its status file and compacts
// its journal): each complete line is handed out once.
class FileFollower {
 public:
  explicit FileFollower(std::string path) : path_(std::move(path)) {}

  // Reads what was appended, line by line. When the file is not the one
  // read before, `on_replaced` comes first (what was counted from the old
  // one no longer holds), then every line of the new one. Returns false
  // when the file is not there (yet).
  template <class OnReplaced, class OnLine>
  bool refresh(OnReplaced on_replaced, OnLine on_line) {
    int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
      ::close(fd);
      return false;
    }
    if (!same_file(fd, st)) {
      restart(st);
      on_replaced();
    }
    std::string fresh;
    char buf[65536];
    for (;;) {
      ssize_t n = ::pread(fd, buf, sizeof buf, static_cast<off_t>(offset_ + fresh.size()));
      if (n <= 0) break;
      fresh.append(buf, static_cast<std::size_t>(n));
    }
    ::close(fd);
    // Only complete lines: a last line without its newline is still being
    // written, and is read again next time.
    std::size_t begin = 0;
    for (std::size_t end = fresh.find('\n'); end != std::string::npos; end = fresh.find('\n', begin)) {
      on_line(fresh.substr(begin, end - begin));
      begin = end + 1;
    }
    std::size_t keep = std::min(begin, kTail);  // a first look can read megabytes
    consumed_tail_.append(fresh, begin - keep, keep);
    if (consumed_tail_.size() > kTail) consumed_tail_.erase(0, consumed_tail_.size() - kTail);
    offset_ += begin;
    return true;
  }

 private:
  static constexpr std::size_t kTail = 256;

  // The same file grown: same inode, not shorter, and the bytes before
  // where the last look stopped unchanged (the file renamed over it can get
  // the inode number the old one freed).
  bool same_file(int fd, const struct stat& st) const {
    if (st.st_dev != dev_ || st.st_ino != ino_ || st.st_size < static_cast<off_t>(offset_)) return false;
    if (consumed_tail_.empty()) return true;
    std::string check(consumed_tail_.size(), '\0');
    off_t from = static_cast<off_t>(offset_ - consumed_tail_.size());
    return ::pread(fd, check.data(), check.size(), from) == static_cast<ssize_t>(check.size()) &&
           check == consumed_tail_;
  }

  void restart(const struct stat& st) {
    dev_ = st.st_dev;
    ino_ = st.st_ino;
    offset_ = 0;
    consumed_tail_.clear();
  }

  std::string path_;
  dev_t dev_ = 0;
  ino_t ino_ = 0;
  std::size_t offset_ = 0;     // bytes of complete lines already read
  std::string consumed_tail_;  // the last bytes before offset_
};

// A basic regular expression matched against one line; none matches every line.
class LinePattern {
 public:
  LinePattern() = default;
  LinePattern(const LinePattern&) = delete;
  LinePattern& operator=(const LinePattern&) = delete;
  ~LinePattern() {
    if (compiled_) ::regfree(&regex_);
  }
  bool compile(const char* text) {
    if (compiled_) ::regfree(&regex_);
    compiled_ = ::regcomp(&regex_, text, REG_NOSUB) == 0;
    return compiled_;
  }
  bool set() const { return compiled_; }
  bool matches(const std::string& line) const {
    return !compiled_ || ::regexec(&regex_, line.c_str(), 0, nullptr, 0) == 0;
  }

 private:
  regex_t regex_{};
  bool compiled_ = false;
};

template <typename Number>
bool parse_number(std::string_view text, Number& value) {
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

void pause_for(double seconds) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(seconds);
  ts.tv_nsec = static_cast<long>((seconds - static_cast<double>(ts.tv_sec)) * 1e9);
  while (::nanosleep(&ts, &ts) != 0 && errno == EINTR) {
  }
}

struct Wait {
  LinePattern match, after;
  long at_least = 1;
  long tries = 1000;
  double every = 0.01;
  pid_t while_alive = 0;
  const char* file = nullptr;
};

bool parse(int argc, char** argv, Wait& w) {
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    if (i + 1 == argc) {
      w.file = argv[i];
      return !arg.starts_with("--");
    }
    const char* value = argv[++i];
    long pid = 0;
    bool ok = arg == "--match"         ? w.match.compile(value)
              : arg == "--after"       ? w.after.compile(value)
              : arg == "--at-least"    ? parse_number(value, w.at_least)
              : arg == "--tries"       ? parse_number(value, w.tries)
              : arg == "--every"       ? parse_number(value, w.every)
              : arg == "--while-alive" ? parse_number(value, pid) && pid > 0
                                       : false;
    if (!ok) return false;
    if (pid > 0) w.while_alive = static_cast<pid_t>(pid);
  }
  return false;
}

bool gone(pid_t pid) { return pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH; }

}  // namespace

int main(int argc, char** argv) {
  Wait w;
  if (!parse(argc, argv, w)) {
    std::fputs(
        "usage: gctest-wait [--match RE] [--after RE] [--at-least N] [--tries N] [--every SECONDS] "
        "[--while-alive PID] FILE\n",
        stderr);
    return 2;
  }
  FileFollower file(w.file);
  long counted = 0;
  bool after_seen = !w.after.set();
  for (long i = 0; i < w.tries; ++i) {
    file.refresh(
        [&] {
          counted = 0;
          after_seen = !w.after.set();
        },
        [&](const std::string& line) {
          if (!after_seen && w.after.matches(line)) after_seen = true;
          if (after_seen && w.match.matches(line)) ++counted;
        });
    if (after_seen && counted >= w.at_least) return 0;
    if (gone(w.while_alive)) return 1;
    pause_for(w.every);
  }
  return 1;
}
