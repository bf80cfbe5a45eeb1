// gc-send's `cancel object` and --exclude on the in-process virtual printer,
// the 12 pegs of a PrusaSlicer plate (its first 14 layers). What the printer
// executed is held against the file by the independent replay checker of
// gc-objects (tests/support/objects/object_check.hpp), which shares no code
// with the tool: every other object's extrusion once, in order, with the
// same ends and filament, primed (retracted) before each exactly as in the
// file, and nothing of the cancelled one from the moment it took effect.
//
// A cancel mid-print takes effect after the input line gc-send names; the
// file the checker is given calls the cancelled object's blocks up to that
// line another object (their lines are the same), so that "left out" means
// "left out from there": at a block's start, in the middle of a block (a
// `pause now`, then `cancel object` while paused, applied at the resume),
// during the rushed rest of a layer, and while printing at full speed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "control_run.hpp"
#include "objects/object_check.hpp"
#include "test_support.hpp"

using gctest::quote;
using gctest::tool_path;

namespace test_gc_send_objects {

constexpr const char* kPegsPrinter = "time-scale=20,instant-moves,heat-rate=1000";

// The pegs plate up to layer 14 (its first 14000 lines): a print of a few seconds.
std::string pegs() {
  static const std::string path = [] {
    std::string text = gctest::read_file(gctest::fixture_path("prusa_pegs_0.2_klipper_zhop_labels.gcode"));
    std::size_t at = 0;
    for (int i = 0; i < 14000; ++i) at = text.find('\n', at) + 1;
    std::string p = gctest::temp_dir() + "/pegs14.gcode";
    gctest::write_file(p, std::string_view(text).substr(0, at));
    return p;
  }();
  return path;
}

std::string executed_text(const std::vector<gctest::Executed>& log) {
  std::string out;
  for (const gctest::Executed& e : log) out += e.command + "\n";
  return out;
}

// `input` with object `id`'s blocks up to line `after` (1-based) relabelled
// "was<id>": what the printer was meant to print of it before the cancel.
std::string printed_before(const std::string& input, const std::string& id, std::uint64_t after) {
  const std::string mark = " id:" + id + " copy";
  std::string out, start;
  bool open = false;
  std::uint64_t n = 0;
  for (const std::string& line : gctest::split_lines(input)) {
    ++n;
    std::string l = line;
    const bool label = l.find("printing object ") != std::string::npos && l.find(mark) != std::string::npos;
    if (label && n <= after) {
      open = l.find("stop printing object") == std::string::npos;
      if (open) start = l.substr(0, l.find_first_of("\r\n"));
      l.replace(l.find(mark), mark.size(), " id:was" + id + " copy");
    }
    out += l;
    if (n == after && open) {
      // In the middle of its block: the rest of the block is the object's.
      std::string stop = start;
      stop.replace(stop.find("printing object"), 15, "stop printing object");
      stop.replace(stop.find(mark), mark.size(), " id:was" + id + " copy");
      out += stop + "\n" + start + "\n";
    }
  }
  return out;
}

// What the script said it cancelled.
std::string cancelled_id(const std::string& err) {
  std::size_t p = err.find("cancelled id: ");
  REQUIRE(p != std::string::npos);
  return err.substr(p + 14, err.find('\n', p) - p - 14);
}

// The status file of a run (next to its control FIFO, which gc-send -v names).
std::string status_of(const std::string& err) {
  std::size_t p = err.find("control FIFO: ");
  REQUIRE(p != std::string::npos);
  std::string fifo = err.substr(p + 14, err.find('\n', p) - p - 14);
  return gctest::read_file(fifo.substr(0, fifo.rfind('/')) + "/status.json");
}

// "cancel object ID (NAME): ... after input line N": N.
std::uint64_t cancelled_after(const std::string& err, const std::string& id) {
  std::size_t p = err.find("cancel object " + id + " (");
  REQUIRE(p != std::string::npos);
  std::size_t q = err.find(" after input line ", p);
  REQUIRE(q != std::string::npos);
  return std::stoull(err.substr(q + 18, 12));
}

void require_checked(const std::string& input, const std::vector<gctest::Executed>& log,
                     const std::vector<std::string>& left_out) {
  const gctest::ObjectCheck c = gctest::check_objects_left_out(input, executed_text(log), left_out);
  INFO(c.message);
  REQUIRE(c.ok);
  CHECK(c.kept > 1000);
  CHECK(c.left_out > 0);
  CHECK(log.back().command == "M400");
}

// The object the status file says is printing (its id), in the shell.
const char* const kPrinting =
    "id=$(grep -o '\"id\": \"[^\"]*\", \"name\": \"[^\"]*\", \"state\": \"printing\"' \"$S\" | cut -d'\"' -f4)";

// Where an object's extrusions end in the file: its box on the plate, and
// the ends of those up to line `after`.
struct ObjectPlace {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  std::set<std::string> before;
};

std::string end_key(const gcode::MachineState& m) {
  return fmt::format("{:.3f} {:.3f} {:.3f}", m.position[gcode::kX], m.position[gcode::kY], m.position[gcode::kZ]);
}

// Whether a line extrudes while it moves in XY.
bool extrudes(const gcode::Line& l, const gcode::MachineState& before, const gcode::MachineState& after) {
  return (l.is_g(1) || l.is_g(0)) && after.position[gcode::kE] > before.position[gcode::kE] &&
         (after.position[gcode::kX] != before.position[gcode::kX] || after.position[gcode::kY] != before.position[gcode::kY]);
}

ObjectPlace place_of(const std::string& input, const std::string& id, std::uint64_t after) {
  ObjectPlace p;
  gcode::MachineState s = gctest::initial_state(input);
  bool inside = false;
  std::uint64_t n = 0;
  for (const std::string& line : gctest::split_lines(input)) {
    ++n;
    if (line.find("printing object ") != std::string::npos && line.find(" id:" + id + " copy") != std::string::npos)
      inside = line.find("stop printing") == std::string::npos;
    std::string_view text = line;
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
    const gcode::MachineState before = s;
    const gcode::Line l = gcode::Line::parse(text);
    s.apply(l);
    if (!inside || !extrudes(l, before, s)) continue;
    p.x0 = std::min(p.x0, s.position[gcode::kX]);
    p.y0 = std::min(p.y0, s.position[gcode::kY]);
    p.x1 = std::max(p.x1, s.position[gcode::kX]);
    p.y1 = std::max(p.y1, s.position[gcode::kY]);
    if (n <= after) p.before.insert(end_key(s));
  }
  REQUIRE(p.x1 > p.x0);
  return p;
}

// The printer's state after each extrusion it ran that ends on `place`.
std::vector<gcode::MachineState> extrusions_on(const std::vector<gctest::Executed>& log, const ObjectPlace& place) {
  std::vector<gcode::MachineState> found;
  gcode::MachineState p;
  for (const gctest::Executed& e : log) {
    const gcode::MachineState before = p;
    const gcode::Line l = gcode::Line::parse(e.command);
    p.apply(l);
    const double x = p.position[gcode::kX], y = p.position[gcode::kY];
    if (extrudes(l, before, p) && x >= place.x0 - 0.01 && x <= place.x1 + 0.01 && y >= place.y0 - 0.01 &&
        y <= place.y1 + 0.01)
      found.push_back(p);
  }
  return found;
}

// gc-send on the pegs with `script` (which cancels one object and says
// which on stderr), checked from the line gc-send says the cancel took
// effect after.
gctest::PauseRun cancel_run(const std::string& args, const std::string& script) {
  gctest::PauseRun r = gctest::send_with_control(pegs(), kPegsPrinter, args, script);
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  const std::string id = cancelled_id(r.result.err);
  require_checked(printed_before(gctest::read_file(pegs()), id, cancelled_after(r.result.err, id)), r.log, {id});
  return r;
}

}  // namespace test_gc_send_objects

using namespace test_gc_send_objects;

TEST_CASE("gc-send --exclude: the objects are left out from the start, the rest printed as in the file",
          "[gc-send][objects]") {
  const std::string input = gctest::read_file(pegs());
  gctest::PauseRun r = gctest::send_with_control(pegs(), kPegsPrinter, "--no-pace --exclude 2,pegs.stl_5,nosuch", "true");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  require_checked(input, r.log, {"2", "4"});
  CHECK(r.result.err.find("objects left out: 2 (pegs.stl_3), 4 (pegs.stl_5)") != std::string::npos);
  CHECK(r.result.err.find("--exclude nosuch: no such object in the print") != std::string::npos);
  // The status file lists the objects, the excluded ones as cancelled.
  const std::string status = status_of(r.result.err);
  CHECK(status.find("{\"id\": \"2\", \"name\": \"pegs.stl_3\", \"state\": \"cancelled\"}") != std::string::npos);
  CHECK(status.find("{\"id\": \"6\", \"name\": \"pegs.stl_7\", \"state\": \"kept\"}") != std::string::npos);
  CHECK(status.find("\"cancelled\": [\"2 (pegs.stl_3)\", \"4 (pegs.stl_5)\", \"nosuch\"]") != std::string::npos);
}

TEST_CASE("gc-send cancel object while printing: nothing of it from the line named, the rest as in the file",
          "[gc-send][objects]") {
  struct Moment {
    int layer;
    const char* delay;
  };
  for (Moment m : {Moment{2, "0"}, Moment{4, "0.07"}, Moment{7, "0.19"}}) {
    INFO("layer " << m.layer << ", then " << m.delay << " s");
    gctest::PauseRun r = cancel_run(
        "--no-pace", "at_layer " + std::to_string(m.layer) + "; sleep " + m.delay + "; " + kPrinting +
                         "; [ -n \"$id\" ] || id=8; echo \"cancel object $id\" > \"$F\"; echo objects > \"$F\"; "
                         "echo \"cancelled id: $id\" >&2");
    CHECK(r.result.err.find("objects: 12 (PrusaSlicer labels)") != std::string::npos);
  }
}

TEST_CASE("gc-send cancel object during a pause's rush and while paused: applied where it was asked",
          "[gc-send][objects]") {
  SECTION("during the rush: the rest of the layer goes on without it") {
    gctest::PauseRun r = cancel_run("--no-pace --rush 3",
                                    std::string("at_layer 5; echo pause > \"$F\"; ") + kPrinting +
                                        "; [ -n \"$id\" ] || id=7; echo \"cancel object $id\" > \"$F\"; "
                                        "echo \"cancelled id: $id\" >&2; paused; echo resume > \"$F\"");
    CHECK(r.result.err.find("at 3 times the speed") != std::string::npos);
  }
  SECTION("paused in the middle of a block: its block ends at the resume") {
    gctest::PauseRun r = cancel_run("--no-pace",
                                    std::string("at_layer 6; echo 'pause now' > \"$F\"; paused; ") + kPrinting +
                                        "; [ -n \"$id\" ] || id=5; echo \"cancel object $id\" > \"$F\"; "
                                        "echo \"cancelled id: $id\" >&2; sleep 0.2; echo resume > \"$F\"");
    CHECK(r.result.err.find("its block ends there") != std::string::npos);
  }
}

TEST_CASE("gc-send cancel object: unknown, repeated and last objects are refused or kept for later",
          "[gc-send][objects]") {
  gctest::PauseRun r = gctest::send_with_control(
      pegs(), kPegsPrinter, "--no-pace",
      "at_layer 2; echo 'cancel object' > \"$F\"; echo 'cancel object 3 3 \"later part\"' > \"$F\"; "
      "echo 'cancel object 3' > \"$F\"; echo objects > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("'cancel object' needs an argument") != std::string::npos);
  CHECK(r.result.err.find("cancel object later part: no such object so far; it is left out if it appears") !=
        std::string::npos);
  CHECK(r.result.err.find("is cancelled already") != std::string::npos);
  CHECK(r.result.err.find("cancel object later part: no such object in the print") != std::string::npos);
  CHECK(r.result.err.find("later part") != std::string::npos);
  CHECK(r.result.err.find("cancelled (cancel object), not seen yet") != std::string::npos);
}

TEST_CASE("gc-send --resume after kill -9: the objects cancelled and excluded stay left out", "[gc-send][objects]") {
  // gc-virtual-printer on a pty runs on when gc-send is killed; the resumed
  // gc-send is given no --exclude: the journal's list is what leaves them out.
  const std::string dir = gctest::temp_dir();
  const std::string port = dir + "/printer", journal = dir + "/print.journal", fifo = dir + "/control.fifo";
  const std::string first = dir + "/first.err";
  const std::string send = quote(tool_path("gc-send")) + " -v --port " + quote(port) + " --journal " + quote(journal);
  // The cancel goes once the printer has run what comes before input line
  // 450 (inside object 2 in layer 1: lines 390 to 501, so gc-send has seen
  // it), the kill once it has run 300 commands more: counts, not times.
  std::size_t inside_2 = 0;
  for (const gctest::SentCommand& c : gctest::commands_of(gctest::read_file(pegs()))) inside_2 += c.source_line < 450 ? 1 : 0;
  const std::string log = quote(dir + "/executed.log");
  auto printer_ran = [&](const std::string& count) {
    return gctest::wait_for_lines(log, {.match = gctest::numbered_log_line(), .at_least = count, .while_alive = "$gs"});
  };
  const std::string script =
      quote(tool_path("gc-virtual-printer")) + " -q --time-scale 8 --instant-moves --heat-rate 1000 --link " +
      quote(port) + " --log " + quote(dir + "/executed.log") + " & vp=$!\n" + gctest::wait_for_link(port) + send +
      " --no-pace --exclude 6 --control " + quote(fifo) + " " + quote(pegs()) + " 2> " + quote(first) + " & gs=$!\n" +
      gctest::wait_for_fifo(fifo) + printer_ran(std::to_string(inside_2)) + "echo 'cancel object 2' > " + quote(fifo) +
      "\nn=$(" + gctest::numbered_log_count(dir + "/executed.log") + ")\n" + printer_ran("$((n + 300))") +
      "kill -9 $gs; wait $gs 2>/dev/null\n" + send + " --no-control --resume " +
      quote(journal) + " " + quote(pegs()) + "; s=$?; kill $vp; wait $vp; exit $s";
  auto r = gctest::run(script);
  const std::string first_err = gctest::read_file(first);
  INFO(first_err);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.find("resuming: ") != std::string::npos);
  CHECK(r.err.find("objects left out: 6 (pegs.stl_7), 2 (pegs.stl_3)") != std::string::npos);
  const auto executed = gctest::parse_executed_log(gctest::read_file(dir + "/executed.log"));
  std::string text;
  for (const std::string& c : executed.commands) text += c + "\n";
  // Left out from the line the cancel took effect after, or from where the
  // resumed print went on if the printer had not got that far.
  const auto resumed_from = static_cast<std::uint64_t>(gctest::number_after(r.err, "; on from input line "));
  REQUIRE(resumed_from > 0);
  // (On a loaded machine the cancel may come before object 2 first
  // appears: then none of it is printed.)
  const bool before_it = first_err.find("cancel object 2: no such object so far") != std::string::npos;
  const std::uint64_t after = before_it ? 0 : std::min(cancelled_after(first_err, "2"), resumed_from - 1);
  const gctest::ObjectCheck c =
      gctest::check_objects_left_out(printed_before(gctest::read_file(pegs()), "2", after), text, {"6", "2"});
  INFO(c.message);
  REQUIRE(c.ok);
  CHECK(c.kept > 1000);
}

TEST_CASE("gc-send cancel object right before a printer reset: after the way back, nothing of it is printed again",
          "[gc-send][objects]") {
  // The reset's way back repeats what the printer lost: moves from before
  // the cancel may run twice (they are the file's), none of the object's
  // after it. Each extrusion that ends on the object's place on the plate
  // must be one of its extrusions up to the line the cancel took effect after.
  gctest::PauseRun r = gctest::send_with_control(
      pegs(), std::string(kPegsPrinter) + ",reset@layer=6", "--no-pace",
      std::string("at_layer 5; ") + kPrinting +
          "; [ -n \"$id\" ] || id=9; echo \"cancel object $id\" > \"$F\"; echo \"cancelled id: $id\" >&2");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  CHECK(r.result.err.find("1 reset") != std::string::npos);
  const std::string id = cancelled_id(r.result.err);
  const std::uint64_t after = cancelled_after(r.result.err, id);
  const ObjectPlace place = place_of(gctest::read_file(pegs()), id, after);
  std::size_t on_place = 0;
  for (const gcode::MachineState& at : extrusions_on(r.log, place)) {
    ++on_place;
    INFO("an extrusion to " << end_key(at));
    REQUIRE(place.before.count(end_key(at)) == 1);
  }
  CHECK(on_place > 0);
}

TEST_CASE("gc-send cancel object and --exclude in a swapped-in file: its objects of those ids are left out too",
          "[gc-send][objects]") {
  // The pegs' first 14 layers swapped at layer 4 for the whole plate (the
  // same objects, labelled alike); object 2 excluded from the start, object
  // 9 cancelled once the swap is asked for.
  const std::string whole = gctest::fixture_path("prusa_pegs_0.2_klipper_zhop_labels.gcode");
  gctest::PauseRun r = gctest::send_with_control(
      pegs(), kPegsPrinter, "--no-pace --exclude 2",
      "at_layer 4; echo \"swap " + whole + "\" > \"$F\"; sleep 0.05; echo 'cancel object 9' > \"$F\"");
  INFO(r.result.err);
  REQUIRE(r.result.status == 0);
  const double joined_layer = gctest::number_after(r.result.err, ": joined onto layer ");
  REQUIRE(joined_layer >= 4);
  const double z = gctest::number_after(r.result.err.substr(r.result.err.find(": joined onto layer ")), "(Z ");
  REQUIRE(z > 0.5);
  const std::string input = gctest::read_file(whole);
  CHECK(extrusions_on(r.log, place_of(input, "2", 0)).empty());
  std::size_t above = 0;
  for (const gcode::MachineState& at : extrusions_on(r.log, place_of(input, "9", 0))) {
    INFO("an extrusion of object 9 at " << end_key(at));
    CHECK(at.position[gcode::kZ] <= z + 1e-6);
  }
  for (const gcode::MachineState& at : extrusions_on(r.log, place_of(input, "7", 0)))
    if (at.position[gcode::kZ] > z + 1e-6) ++above;
  CHECK(above > 100);
  CHECK(r.result.err.find("objects left out: 2 (pegs.stl_3), 9 (pegs.stl_10)") != std::string::npos);
}
