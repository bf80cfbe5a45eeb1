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
#include <regex.h>
#include <signal.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
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

// Whether the file holds what is waited for (a missing file does not).
bool found(const Wait& w, const Regex& pattern, const Regex* after) {
  std::ifstream in(w.file, std::ios::binary);
  if (!in) return false;
  long seen = 0;
  bool counting = after == nullptr;
  for (std::string line; std::getline(in, line);) {
    if (!counting && after->matches(line)) counting = true;
    if (counting && w.count <= 0) return true;  // the --after line is all that is waited for
    if (counting && pattern.matches(line) && ++seen >= w.count) return true;
  }
  return false;
}

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
  const auto pause = std::chrono::duration<double>(w.pause);
  const auto deadline = std::chrono::steady_clock::now() + 2 * w.tries * pause;
  while (std::chrono::steady_clock::now() < deadline) {
    if (found(w, pattern, w.after.empty() ? nullptr : &after)) return 0;
    if (w.alive > 0 && ::kill(static_cast<pid_t>(w.alive), 0) != 0 && errno == ESRCH) return 0;
    std::this_thread::sleep_for(pause);
  }
  return 0;
}
