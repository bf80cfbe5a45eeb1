#include "gcode/serial/journal/journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "gcode/serial/link/private_path.hpp"

namespace gcode::serial {

namespace {

constexpr std::string_view kFormat = "gc-send-journal/1";

std::string errno_text() { return std::strerror(errno); }

void write_all(int fd, std::string_view text, const std::string& path) {
  while (!text.empty()) {
    ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw JournalError(fmt::format("cannot write the journal {}: {}", path, errno_text()));
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

void sync_folder(const std::string& path) {
  int dir = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return;
  ::fsync(dir);  // the rename itself survives a power loss
  ::close(dir);
}

// A path that exists must be this user's own regular file, not a link.
void check_existing(const std::string& path) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    throw JournalError(fmt::format("journal {}: {}", path, errno_text()));
  }
  if (!S_ISREG(st.st_mode)) throw JournalError(fmt::format("journal refused: {} is not a regular file", path));
  if (st.st_uid != ::getuid())
    throw JournalError(fmt::format("journal refused: {} belongs to another user (uid {})", path, st.st_uid));
}

void check_folder(const std::string& path) {
  std::string problem = folder_problem(folder_of(path), "journal");
  if (!problem.empty()) throw JournalError(problem);
}

// A fresh file beside `path`, written whole and synced before it replaces
// `path`: a crash leaves either the old journal or the new one.
int replace_with(const std::string& path, const std::string& text) {
  std::string tmp = fmt::format("{}.tmp-{}", path, ::getpid());
  ::unlink(tmp.c_str());
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (fd < 0) throw JournalError(fmt::format("cannot create the journal {}: {}", tmp, errno_text()));
  try {
    write_all(fd, text, tmp);
    if (::fdatasync(fd) != 0) throw JournalError(fmt::format("cannot sync the journal {}: {}", tmp, errno_text()));
    if (::rename(tmp.c_str(), path.c_str()) != 0)
      throw JournalError(fmt::format("cannot replace the journal {}: {}", path, errno_text()));
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  sync_folder(path);
  return fd;
}

JournalRecord point_record(char type, std::uint64_t n, const JournalFields& fields) {
  JournalRecord r{type, {}};
  r.fields.set("n", std::to_string(n));
  r.fields.update(fields);
  return r;
}

JournalRecord ack_record(std::uint64_t n) {
  JournalRecord r{'A', {}};
  r.fields.set("n", std::to_string(n));
  return r;
}

}  // namespace

std::string default_journal_path(std::string_view port) {
  std::string dir = state_folder();
  if (dir.empty()) dir = fmt::format("/tmp/gc-send-{}", ::getuid());
  return dir + "/" + port_file_name(port) + ".journal";
}

JournalWriter::JournalWriter(JournalOptions options, JournalFields header, std::vector<JournalEntry> carried)
    : options_(std::move(options)), header_(std::move(header)) {
  header_.set("format", std::string(kFormat));
  make_private_folder(options_.path);
  check_folder(options_.path);
  check_existing(options_.path);
  if (!carried.empty()) acked_ = carried.back().n;
  for (JournalEntry& e : carried) {
    JournalFields changes = have_last_ ? e.point.changed_since(last_) : JournalFields();
    last_ = std::move(e.point);
    have_last_ = true;
    keep(e.n, std::move(changes));
  }
  std::string text = snapshot();
  fd_ = replace_with(options_.path, text);
  file_bytes_ = text.size();
  bytes_total_ += text.size();
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::sent(std::uint64_t n, const JournalFields& point) {
  if (finished_) return;
  if (!have_last_) {
    last_ = point;
    buffer_ += encode_journal_record(point_record('S', n, point));
    have_last_ = true;
    keep(n, {});
    return;
  }
  JournalFields changes = point.changed_since(last_);
  buffer_ += encode_journal_record(point_record('D', n, changes));
  last_.update(changes);
  keep(n, std::move(changes));
}

// Point n, as its changes since the one kept before it.
void JournalWriter::keep(std::uint64_t n, JournalFields changes) {
  // (With nothing kept before it, the changes since nothing are all of it.)
  kept_.emplace_back(n, kept_.empty() ? last_ : std::move(changes));
  trim_kept();
}

// The newest `keep`, and as many up to the acknowledged line: a resume
// after a reset walks back from that line over what the printer may have
// lost, however far the sender numbered ahead of it (a few, or a batch);
// kMaxKept bounds a printer that never answers. The second oldest becomes
// the full point.
void JournalWriter::trim_kept() {
  while (kept_.size() > options_.keep && (kept_[options_.keep].first <= acked_ || kept_.size() > kMaxKept)) {
    if (kept_.size() > 1) {
      JournalFields full = std::move(kept_[0].second);
      full.update(kept_[1].second);
      kept_[1].second = std::move(full);
    }
    kept_.pop_front();
  }
}

void JournalWriter::acknowledged(std::uint64_t n) {
  if (finished_ || n <= acked_) return;
  acked_ = n;
  buffer_ += encode_journal_record(ack_record(n));
}

void JournalWriter::write_out(const std::string& text) {
  write_all(fd_, text, options_.path);
  file_bytes_ += text.size();
  bytes_total_ += text.size();
  unsynced_ = true;
}

void JournalWriter::flush(double now) {
  if (finished_ || fd_ < 0) return;
  if (!buffer_.empty()) {
    write_out(buffer_);
    buffer_.clear();
  }
  if (file_bytes_ > options_.compact_bytes) compact();
  if (unsynced_ && (sync_soon_ || now - last_sync_ >= options_.sync_interval)) sync(now);
}

void JournalWriter::sync(double now) {
  if (::fdatasync(fd_) != 0)
    throw JournalError(fmt::format("cannot sync the journal {}: {}", options_.path, errno_text()));
  unsynced_ = false;
  sync_soon_ = false;
  last_sync_ = now;
  ++syncs_;
}

// The header, the kept points (a full one, then deltas) and the
// acknowledged line: a whole journal as of now.
std::string JournalWriter::snapshot() const {
  std::string text = encode_journal_record({'H', header_});
  bool first = true;
  for (const auto& [n, fields] : kept_) {
    text += encode_journal_record(point_record(first ? 'S' : 'D', n, fields));
    first = false;
  }
  if (acked_ > 0) text += encode_journal_record(ack_record(acked_));
  return text;
}

void JournalWriter::compact() {
  std::string text = snapshot();
  int fd = replace_with(options_.path, text);
  ::close(fd_);
  fd_ = fd;
  file_bytes_ = text.size();
  bytes_total_ += text.size();
  unsynced_ = false;  // replace_with synced it
  ++compactions_;
}

void JournalWriter::finish(double now) {
  if (finished_ || fd_ < 0) return;
  buffer_ += encode_journal_record({'F', {}});
  sync_soon_ = true;
  flush(now);
  finished_ = true;
  ::close(fd_);
  fd_ = -1;
}

const JournalEntry* JournalContents::at_or_before(std::uint64_t n) const {
  for (auto it = entries.rbegin(); it != entries.rend(); ++it)
    if (it->n <= n) return &*it;
  return nullptr;
}

namespace {

std::string read_whole(const std::string& path) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) {
    if (errno == ENOENT) throw JournalError(fmt::format("no journal at {} (nothing to resume)", path));
    throw JournalError(fmt::format("cannot read the journal {}: {}", path, errno_text()));
  }
  std::string text;
  char buf[65536];
  for (;;) {
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      throw JournalError(fmt::format("cannot read the journal {}: {}", path, errno_text()));
    }
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return text;
}

std::uint64_t number_field(const JournalRecord& r, const std::string& path, std::size_t line) {
  const std::string* v = r.fields.find("n");
  if (v == nullptr || v->empty() || v->find_first_not_of("0123456789") != std::string::npos)
    throw JournalError(fmt::format("journal {} line {}: a record without its line number", path, line));
  return std::stoull(*v);
}

// Applies one good record; returns false for a type it does not know.
bool apply_record(JournalContents& c, const JournalRecord& r, const std::string& path, std::size_t line) {
  switch (r.type) {
    case 'S':
    case 'D': {
      JournalEntry e;
      e.n = number_field(r, path, line);
      if (r.type == 'D') {
        if (c.entries.empty())
          throw JournalError(fmt::format("journal {} line {}: a change before any full record", path, line));
        e.point = c.entries.back().point;
      }
      JournalFields changes = r.fields;
      changes.erase("n");
      e.point.update(changes);
      // A number given again: the commands numbered from it on were taken
      // back before they were sent (a pause now, a cancel) and never ran.
      while (!c.entries.empty() && c.entries.back().n >= e.n) c.entries.pop_back();
      c.entries.push_back(std::move(e));
      return true;
    }
    case 'A': c.acknowledged = number_field(r, path, line); return true;
    case 'F': c.finished = true; return true;
    default: return false;
  }
}

}  // namespace

JournalContents read_journal(const std::string& path) {
  check_folder(path);
  check_existing(path);
  std::string text = read_whole(path);
  JournalContents c;
  std::size_t pos = 0;
  std::size_t line_no = 0;
  std::size_t bad_line = 0;  // the first line that did not check (0: none)
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    std::string_view line(text.data() + pos, (end == std::string::npos ? text.size() : end) - pos);
    pos = end == std::string::npos ? text.size() : end + 1;
    ++line_no;
    auto record = decode_journal_record(line);
    if (!record) {
      if (bad_line == 0) bad_line = line_no;
      continue;
    }
    if (bad_line != 0)
      throw JournalError(fmt::format("journal {} is corrupt: line {} is damaged and good records follow it", path,
                                     bad_line));
    if (c.records == 0) {
      if (record->type != 'H' || record->fields.get("format") != kFormat)
        throw JournalError(fmt::format("{} is not a gc-send journal (or another version of one)", path));
      c.header = record->fields;
    } else if (!apply_record(c, *record, path, line_no)) {
      throw JournalError(fmt::format("journal {} line {}: an unknown record '{}'", path, line_no, record->type));
    }
    ++c.records;
  }
  if (c.records == 0 && bad_line != 0)
    throw JournalError(fmt::format("{} is not a gc-send journal (no readable record)", path));
  if (c.records == 0) throw JournalError(fmt::format("journal {} is empty", path));
  c.torn_tail = bad_line != 0;
  return c;
}

}  // namespace gcode::serial
