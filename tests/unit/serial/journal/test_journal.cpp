// gc-send's journal (gcode/serial/journal/journal.hpp, journal_record.hpp,
// input_identity.hpp, private_path.hpp): records that check themselves,
// every point read back after a crash at any byte, deltas that rebuild the
// full point, a bounded size on a long print, and files refused where others
// could swap them.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gcode/serial/journal/input_identity.hpp"
#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/link/private_path.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

namespace {

JournalFields point(int i) {
  JournalFields f;
  f.set("line", std::to_string(100 + i));
  f.set("off", std::to_string(4000 + 28 * i));
  f.set("layer", std::to_string(1 + i / 50));
  f.set("x", std::to_string(10 + i % 7) + ".25");
  f.set("y", "87.4");
  f.set("e", std::to_string(i) + ".5");
  f.set("f", i % 10 == 0 ? "1800" : "2400");
  f.set("g91", "0");
  return f;
}

JournalFields header() {
  JournalFields h;
  h.set("input", "/home/a user/part #1.gcode");
  h.set("size", "123456");
  h.set("port", "/dev/ttyACM0");
  return h;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

}  // namespace

TEST_CASE("journal record: round trip with escapes, and every damage seen", "[serial][journal]") {
  JournalRecord r{'D', {}};
  r.fields.set("n", "42");
  r.fields.set("path", "a b=c#d%e\tf");
  r.fields.set("empty", "");
  std::string line = encode_journal_record(r);
  REQUIRE(line.back() == '\n');
  CHECK(line.find("a b") == std::string::npos);  // one field stays one word
  auto back = decode_journal_record(std::string_view(line).substr(0, line.size() - 1));
  REQUIRE(back);
  CHECK(back->type == 'D');
  CHECK(back->fields == r.fields);

  RecordProblem problem = RecordProblem::None;
  std::string body = line.substr(0, line.size() - 1);
  for (std::size_t cut = 0; cut < body.size(); ++cut) {
    INFO("cut at " << cut);
    CHECK_FALSE(decode_journal_record(std::string_view(body).substr(0, cut), &problem));
  }
  std::string flipped = body;
  flipped[3] ^= 0x01;
  CHECK_FALSE(decode_journal_record(flipped, &problem));
  CHECK(problem == RecordProblem::BadCheck);
}

TEST_CASE("journal fields: a delta holds what changed and rebuilds the point", "[serial][journal]") {
  JournalFields a = point(1), b = point(2);
  JournalFields d = b.changed_since(a);
  CHECK(d.find("y") == nullptr);
  CHECK(d.get("x") == b.get("x"));
  JournalFields rebuilt = a;
  rebuilt.update(d);
  CHECK(rebuilt == b);
}

TEST_CASE("journal: every point, the acknowledged line and the end read back", "[serial][journal]") {
  std::string path = gctest::temp_dir() + "/p.journal";
  {
    JournalWriter w({path}, header());
    std::size_t full_points = 0;
    for (int i = 0; i < 120; ++i) {
      w.sent(static_cast<std::uint64_t>(i + 1), point(i));
      if (i >= 4) w.acknowledged(static_cast<std::uint64_t>(i - 3));
      w.flush(i * 0.01);
      full_points += encode_journal_record({'S', point(i)}).size();
    }
    // Deltas keep it small: with an acknowledgement after every command it
    // is still smaller than the full points alone.
    CHECK(w.file_bytes() < full_points);
    w.finish(2.0);
  }
  struct stat st{};
  REQUIRE(::stat(path.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
  JournalContents c = read_journal(path);
  CHECK(c.finished);
  CHECK_FALSE(c.torn_tail);
  CHECK(c.header.get("input") == "/home/a user/part #1.gcode");
  REQUIRE(c.entries.size() == 120);
  for (int i = 0; i < 120; ++i) {
    CHECK(c.entries[static_cast<std::size_t>(i)].n == static_cast<std::uint64_t>(i + 1));
    CHECK(c.entries[static_cast<std::size_t>(i)].point == point(i));
  }
  CHECK(c.acknowledged == 116);
  REQUIRE(c.at_or_before(50) != nullptr);
  CHECK(c.at_or_before(50)->point == point(49));
}

TEST_CASE("journal: commands taken back unsent and numbered again replace their first records", "[serial][journal]") {
  // A pause now: lines 4 and 5 were numbered, taken back before they went
  // out, and the pause block went out as 4, 5, 6; then 4 and 5 again as 7, 8.
  std::string path = gctest::temp_dir() + "/t.journal";
  {
    JournalWriter w({path}, header());
    for (int i : {1, 2, 3, 4, 5}) w.sent(static_cast<std::uint64_t>(i), point(i));
    for (int i : {4, 5, 6}) w.sent(static_cast<std::uint64_t>(i), point(100 + i));
    for (int i : {7, 8}) w.sent(static_cast<std::uint64_t>(i), point(i - 3));
    w.flush(0);
  }
  JournalContents c = read_journal(path);
  REQUIRE(c.entries.size() == 8);
  for (std::size_t k = 0; k < 8; ++k) CHECK(c.entries[k].n == k + 1);
  CHECK(c.entries[2].point == point(3));
  CHECK(c.entries[3].point == point(104));  // the block's, rebuilt from the taken-back line's delta
  CHECK(c.entries[5].point == point(106));
  CHECK(c.entries[7].point == point(5));
}

TEST_CASE("journal: synced at least every interval and at once when asked", "[serial][journal]") {
  std::string path = gctest::temp_dir() + "/sync.journal";
  JournalWriter w({path}, header());
  auto send_at = [&](int i, double now) {
    w.sent(static_cast<std::uint64_t>(i), point(i));
    w.flush(now);
  };
  send_at(1, 10.0);  // the first write is synced
  CHECK(w.syncs() == 1);
  send_at(2, 10.4);
  send_at(3, 10.9);
  CHECK(w.syncs() == 1);
  send_at(4, 11.05);  // a second since the last sync
  CHECK(w.syncs() == 2);
  w.sync_soon();      // a layer began
  send_at(5, 11.1);
  CHECK(w.syncs() == 3);
  w.flush(20.0);      // nothing new: nothing to sync
  CHECK(w.syncs() == 3);
}

TEST_CASE("journal: a crash at any byte reads back to the last complete record", "[serial][journal]") {
  std::string dir = gctest::temp_dir();
  std::string path = dir + "/crash.journal";
  {
    JournalWriter w({path}, header());
    for (int i = 0; i < 30; ++i) {
      w.sent(static_cast<std::uint64_t>(i + 1), point(i));
      w.flush(0);
    }
  }  // no finish: killed
  std::string whole = slurp(path);
  std::size_t header_end = whole.find('\n') + 1;
  std::string cut_path = dir + "/cut.journal";
  for (std::size_t cut = header_end; cut <= whole.size(); ++cut) {
    spit(cut_path, whole.substr(0, cut));
    ::chmod(cut_path.c_str(), 0600);
    JournalContents c = read_journal(cut_path);
    // The complete records before the cut, exactly.
    std::size_t complete = 0;
    for (std::size_t p = header_end; p < cut; ++p)
      if (whole[p] == '\n') ++complete;
    bool partial_line = cut > 0 && whole[cut - 1] != '\n';
    INFO("cut at byte " << cut);
    CHECK_FALSE(c.finished);
    // A record cut just before its newline still checks: it counts.
    std::size_t expect = complete;
    if (partial_line && cut < whole.size() && whole[cut] == '\n') ++expect;
    REQUIRE(c.entries.size() == expect);
    if (expect > 0) CHECK(c.entries.back().point == point(static_cast<int>(expect) - 1));
    CHECK(c.torn_tail == (partial_line && expect == complete));
  }
}

TEST_CASE("journal: a damaged record with good ones after it is refused", "[serial][journal]") {
  std::string path = gctest::temp_dir() + "/bad.journal";
  {
    JournalWriter w({path}, header());
    for (int i = 0; i < 10; ++i) w.sent(static_cast<std::uint64_t>(i + 1), point(i));
    w.flush(0);
  }
  std::string text = slurp(path);
  std::size_t third = 0;
  for (int k = 0; k < 3; ++k) third = text.find('\n', third) + 1;
  text[third + 4] ^= 0x20;
  spit(path, text);
  CHECK_THROWS_WITH(read_journal(path), Catch::Contains("corrupt") && Catch::Contains("line 4"));
}

TEST_CASE("journal: missing, empty, foreign and in an open folder are refused", "[serial][journal]") {
  std::string dir = gctest::temp_dir();
  CHECK_THROWS_WITH(read_journal(dir + "/none.journal"), Catch::Contains("no journal"));
  spit(dir + "/empty.journal", "");
  CHECK_THROWS_WITH(read_journal(dir + "/empty.journal"), Catch::Contains("empty"));
  spit(dir + "/other.journal", "G1 X10\nG1 Y10\n");
  CHECK_THROWS_WITH(read_journal(dir + "/other.journal"), Catch::Contains("not a gc-send journal"));

  std::string open_dir = dir + "/open";
  REQUIRE(::mkdir(open_dir.c_str(), 0777) == 0);
  REQUIRE(::chmod(open_dir.c_str(), 0777) == 0);
  CHECK_THROWS_WITH(JournalWriter({open_dir + "/j.journal"}, header()), Catch::Contains("can be changed by others"));
  // Sticky, like /tmp: only owners may rename there.
  REQUIRE(::chmod(open_dir.c_str(), 01777) == 0);
  CHECK_NOTHROW(JournalWriter({open_dir + "/j.journal"}, header()));

  REQUIRE(::symlink("/etc/passwd", (dir + "/link.journal").c_str()) == 0);
  CHECK_THROWS_WITH(JournalWriter({dir + "/link.journal"}, header()), Catch::Contains("not a regular file"));
}

TEST_CASE("journal: a long print stays bounded and keeps the newest points", "[serial][journal]") {
  std::string path = gctest::temp_dir() + "/long.journal";
  JournalOptions options{path};
  options.compact_bytes = 16 * 1024;
  options.keep = 64;
  JournalWriter w(options, header());
  const int commands = 20000;  // several hours of 0.2 mm pieces at a slow pace
  for (int i = 0; i < commands; ++i) {
    w.sent(static_cast<std::uint64_t>(i + 1), point(i));
    if (i > 10) w.acknowledged(static_cast<std::uint64_t>(i - 10));
    w.flush(i * 0.01);
    REQUIRE(w.file_bytes() <= options.compact_bytes + 4096);
  }
  CHECK(w.compactions() > 10);
  JournalContents c = read_journal(path);
  REQUIRE(c.entries.size() >= 64);
  CHECK(c.entries.back().n == static_cast<std::uint64_t>(commands));
  CHECK(c.entries.back().point == point(commands - 1));
  CHECK(c.entries.front().point == point(static_cast<int>(c.entries.front().n) - 1));
  CHECK(c.acknowledged == static_cast<std::uint64_t>(commands - 11));
  CHECK(c.header.get("port") == "/dev/ttyACM0");
  // No temp file left behind by the rewrites.
  CHECK(::access((path + ".tmp-" + std::to_string(::getpid())).c_str(), F_OK) != 0);
}

TEST_CASE("journal: a compaction keeps the points up to the acknowledged line, however far the sender numbered ahead",
          "[serial][journal]") {
  // A resume after a printer reset walks back from the acknowledged line;
  // with more than `keep` commands numbered after it, keeping only the
  // newest lost it, and the resume went back from the newest instead.
  std::string path = gctest::temp_dir() + "/ahead.journal";
  JournalOptions options{path};
  options.compact_bytes = 8 * 1024;
  options.keep = 32;
  JournalWriter w(options, header());
  for (int i = 0; i < 100; ++i) w.sent(static_cast<std::uint64_t>(i + 1), point(i));
  w.acknowledged(100);
  for (int i = 100; i < 1100; ++i) {  // a batch numbered ahead, none answered
    w.sent(static_cast<std::uint64_t>(i + 1), point(i));
    w.flush(i * 0.01);
  }
  REQUIRE(w.compactions() > 0);
  JournalContents c = read_journal(path);
  CHECK(c.acknowledged == 100);
  const JournalEntry* acked = c.at_or_before(100);
  REQUIRE(acked != nullptr);
  CHECK(acked->n == 100);
  CHECK(acked->point == point(99));
  CHECK(c.entries.front().n <= 100 - 32 + 1);
  CHECK(c.entries.back().n == 1100);
  // Once answered, the old points go at the next compaction.
  w.acknowledged(1100);
  for (int i = 1100; i < 2000; ++i) {
    w.sent(static_cast<std::uint64_t>(i + 1), point(i));
    w.acknowledged(static_cast<std::uint64_t>(i + 1));
    w.flush(i * 0.01);
  }
  c = read_journal(path);
  CHECK(c.entries.front().n > 1100);
}

TEST_CASE("journal: a resume's new journal holds the commands it carries from the moment it replaces the old one",
          "[serial][journal]") {
  // gc-send --resume killed before it wrote anything of its own once left a
  // journal of its header alone: the print could not be resumed again.
  std::string path = gctest::temp_dir() + "/resumed.journal";
  { JournalWriter old({path}, header()); }
  std::vector<JournalEntry> carried;
  for (int i = 0; i < 300; ++i) carried.push_back({static_cast<std::uint64_t>(i + 1), point(i)});
  JournalOptions options{path};
  options.keep = 64;
  JournalWriter w(options, header(), carried);
  // Nothing flushed: the file as a kill -9 would leave it now.
  JournalContents c = read_journal(path);
  REQUIRE(c.entries.size() == 64);  // the newest `keep`, as a compaction keeps them
  CHECK(c.entries.front().n == 300 - 64 + 1);
  for (const JournalEntry& e : c.entries) CHECK(e.point == point(static_cast<int>(e.n) - 1));
  CHECK(c.acknowledged == 300);  // the line the print goes on after
  CHECK_FALSE(c.finished);
  CHECK_FALSE(c.torn_tail);
  CHECK(w.file_bytes() == slurp(path).size());
  // What follows is a delta on the carried point, and reads back after it.
  JournalFields next = point(300);
  w.sent(301, next);
  w.acknowledged(301);
  w.flush(0);
  c = read_journal(path);
  REQUIRE(c.entries.size() == 65);
  CHECK(c.entries.back().n == 301);
  CHECK(c.entries.back().point == point(300));
  CHECK(c.acknowledged == 301);
  const std::string text = slurp(path);
  std::size_t full_points = 0;
  for (std::size_t p = 0; (p = text.find("\nS ", p)) != std::string::npos; ++p) ++full_points;
  CHECK(full_points == 1);  // one full point: the rest are deltas
}

TEST_CASE("input identity: a file's size and time, any stream's prefix hash", "[serial][journal]") {
  std::string path = gctest::temp_dir() + "/in.gcode";
  spit(path, "G28\nG1 X10 E1\n");
  int fd = ::open(path.c_str(), O_RDONLY);
  InputIdentity id = identify_input(path, fd);
  ::close(fd);
  CHECK(id.regular);
  CHECK(id.size == 14);
  CHECK(id.mtime_ns > 0);
  int p[2];
  REQUIRE(::pipe(p) == 0);
  CHECK_FALSE(identify_input("-", p[0]).regular);
  ::close(p[0]);
  ::close(p[1]);

  PrefixHash whole, pieces;
  whole.update("G28\nG1 X10 E1\n");
  pieces.update("G28\n");
  pieces.update("G1 X10");
  pieces.update(" E1\n");
  CHECK(whole.digest() == pieces.digest());
  CHECK(pieces.bytes() == 14);
  PrefixHash other;
  other.update("G28\nG1 X11 E1\n");
  CHECK(other.digest() != whole.digest());
  CHECK(hash_text(whole.digest()).size() == 16);
}

TEST_CASE("private paths: port names and the state folder", "[serial][journal]") {
  CHECK(port_file_name("/dev/serial/by-id/usb-Prusa_MK3_123-if00") == "usb-Prusa_MK3_123-if00");
  CHECK(port_file_name("virtual:time-scale=20") == "virtual");
  CHECK(folder_of("a.journal") == ".");
  CHECK(folder_of("/a.journal") == "/");
  std::string dir = gctest::temp_dir();
  ::setenv("XDG_STATE_HOME", dir.c_str(), 1);
  CHECK(default_journal_path("/dev/ttyACM0") == dir + "/gc-send/ttyACM0.journal");
  ::unsetenv("XDG_STATE_HOME");
  // Every missing folder is made, private.
  std::string deep = dir + "/a/b/c/j.journal";
  make_private_folder(deep);
  struct stat st{};
  REQUIRE(::stat((dir + "/a/b/c").c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0700);
}

TEST_CASE("journal fields: a count reads a whole number, and 0 where a damaged field holds none", "[serial][journal]") {
  gcode::serial::JournalFields f;
  f.set("line", "40");
  f.set("huge", "99999999999999999999999");  // past 64 bits: no exception out of a reader
  f.set("neg", "-3");
  f.set("junk", "12x");
  f.set("empty", "");
  CHECK(f.count("line") == 40);
  CHECK(f.count("huge") == 0);
  CHECK(f.count("neg") == 0);
  CHECK(f.count("junk") == 0);
  CHECK(f.count("empty") == 0);
  CHECK(f.count("missing") == 0);
}
