// gc-pause-at: insert a clean pause (retract, park, wait, resume exactly) at
// layer boundaries. The pause block goes where gcode::LayerTracker says a
// layer begins: after the last move of the previous layer, before the move
// to the new layer's Z. The sequence itself comes from pause_sequence.hpp,
// the bed and height limits from core/print_area.hpp.
#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/core/layer_range.hpp"
#include "gcode/core/layer_tracker.hpp"
#include "gcode/core/line_reader.hpp"
#include "gcode/core/number.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/transform/pause_sequence.hpp"
#include "gcode/core/print_area.hpp"
#include "gcode/cli/io.hpp"

namespace {

constexpr const char* kName = "gc-pause-at";
constexpr const char* kVersion = "gc-pause-at 0.1.0";

// A request the input cannot meet: exit 1 (usage errors exit 2 via CLI11).
// CLI11's own range checks print the largest double in full.
const CLI::Validator kNonNegative(
    [](std::string& v) {
      double d = 0;
      return gcode::parse_number(v, d) && d >= 0 ? std::string() : "must be a number >= 0, not " + v;
    },
    "NUMBER>=0");
const CLI::Validator kPositive(
    [](std::string& v) {
      double d = 0;
      return gcode::parse_number(v, d) && d > 0 ? std::string() : "must be a number > 0, not " + v;
    },
    "NUMBER>0");

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string num(double v, int decimals = 3) {
  char b[gcode::kMaxNumberChars];
  return std::string(gcode::number_text(v, decimals, b));
}

std::vector<double> parse_numbers(const std::string& text, const char* what) {
  std::vector<double> out;
  std::string_view rest = text;
  while (true) {
    std::size_t comma = rest.find(',');
    double v = 0;
    if (!gcode::parse_number(rest.substr(0, comma), v) || !std::isfinite(v))
      throw UsageError(std::string(what) + ": '" + text + "' is not a list of numbers");
    out.push_back(v);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

// "220x220" -> a bed from 0,0.
gcode::Box2 parse_bed(const std::string& text) {
  std::size_t x = text.find_first_of("xX");
  double w = 0, d = 0;
  if (x == std::string::npos || !gcode::parse_number(std::string_view(text).substr(0, x), w) ||
      !gcode::parse_number(std::string_view(text).substr(x + 1), d) || w <= 0 || d <= 0)
    throw UsageError("--bed: '" + text + "' is not WIDTHxDEPTH in mm (e.g. 220x220)");
  return gcode::Box2{0, 0, w, d};
}

// --before/--after/custom: the name of a file, or G-code text where "\n"
// (backslash n) separates lines.
std::string gcode_text(const std::string& value) {
  struct stat st {};
  if (!value.empty() && ::stat(value.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
    std::ifstream in(value, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  std::string out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (value[i] == '\\' && i + 1 < value.size() && value[i + 1] == 'n') {
      out += '\n';
      ++i;
    } else {
      out += value[i];
    }
  }
  return out;
}

std::string expand(std::string text, int layer, double z) {
  auto replace = [&text](const std::string& key, const std::string& value) {
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  };
  replace("{layer}", layer > 0 ? std::to_string(layer) : std::string("end"));
  replace("{z}", num(z));
  return text;
}

struct Where {
  bool has_before = false, has_after = false;
  gcode::LayerRange before, after;
  std::vector<double> heights;
  std::vector<bool> height_used;
  int every = 0;
  int fired_before = 0, fired_after = 0, fired_every = 0;

  // Whether a pause goes before layer `index` (whose Z is `z`).
  bool at_layer(int index, double z) {
    bool hit = false;
    if (has_before && before.contains(index)) {
      hit = true;
      ++fired_before;
    }
    if (has_after && index > 1 && after.contains(index - 1)) {
      hit = true;
      ++fired_after;
    }
    if (every > 0 && index > 1 && (index - 1) % every == 0) {
      hit = true;
      ++fired_every;
    }
    // A Z-hop is no layer, so it never gets here: only layer Z counts
    // (Cura's PauseAtHeight was fooled by hops, Cura #10242).
    for (std::size_t i = 0; i < heights.size(); ++i) {
      if (!height_used[i] && z > heights[i] + 1e-6) {
        height_used[i] = true;
        hit = true;
      }
    }
    return hit;
  }
  bool after_last(int layers) {
    if (has_after && layers > 0 && after.contains(layers)) {
      ++fired_after;
      return true;
    }
    return false;
  }
};

struct Park {
  bool given = false;  // --park
  bool from_bed = false;
  double x = 0, y = 0;
  gcode::PrintArea limits;
};

class PauseWriter : public gcode::LayerSink {
 public:
  PauseWriter(gcode::OutputBuffer& out, bool dry_run, Where& where, const Park& park,
              const gcode::PauseConfig& config, gcode::Diagnostics& diag)
      : out_(out), dry_run_(dry_run), where_(where), park_(park), config_(config), diag_(diag) {
    if (dry_run_) out_.write("# layer\tz\tline\tpark\n");
  }

  void on_layer(const gcode::LayerInfo& layer, const gcode::MachineState& before) override {
    layers_ = layer.index;
    top_layer_z_ = std::max(top_layer_z_, layer.z);
    if (where_.at_layer(layer.index, layer.z)) insert(layer.index, layer.z, layer.first_line, before);
  }

  void on_end_code(std::uint64_t first_line, std::uint64_t, const gcode::MachineState& before) override {
    if (where_.after_last(layers_)) insert(0, before.position[gcode::kZ], first_line, before);
  }

  void on_line(const gcode::TrackedLine& t) override {
    if (!dry_run_) {
      out_.write(t.raw.text);
      out_.write(t.raw.ending);
    }
    if (!t.raw.ending.empty()) ending_ = t.raw.ending == "\r\n" ? "\r\n" : "\n";
    retraction_.observe(t.move);
    if (t.move.extruding) {
      top_z_ = std::max(top_z_, t.move.end[gcode::kZ]);
      if (t.region == gcode::Region::Layer) {
        extend(t.move.start[gcode::kX], t.move.start[gcode::kY]);
        extend(t.move.end[gcode::kX], t.move.end[gcode::kY]);
      }
    }
  }

  int layers() const { return layers_; }
  int pauses() const { return pauses_; }
  double top_layer_z() const { return top_layer_z_; }

 private:
  void extend(double x, double y) {
    if (!has_box_) {
      box_ = gcode::Box2{x, y, x, y};
      has_box_ = true;
      return;
    }
    box_.min_x = std::min(box_.min_x, x);
    box_.min_y = std::min(box_.min_y, y);
    box_.max_x = std::max(box_.max_x, x);
    box_.max_y = std::max(box_.max_y, y);
  }

  // The print's XY extent as far as known: the slicer's header and what was printed.
  bool print_box(gcode::Box2& box) const {
    bool any = false;
    if (park_.limits.has_print_box) {
      box = park_.limits.print_box;
      any = true;
    }
    if (has_box_) {
      if (!any) {
        box = box_;
      } else {
        box.min_x = std::min(box.min_x, box_.min_x);
        box.min_y = std::min(box.min_y, box_.min_y);
        box.max_x = std::max(box.max_x, box_.max_x);
        box.max_y = std::max(box.max_y, box_.max_y);
      }
      any = true;
    }
    return any;
  }

  void insert(int layer, double z, std::uint64_t line, const gcode::MachineState& before) {
    ++pauses_;
    gcode::PauseConfig c = config_;
    gcode::Box2 box;
    bool has_box = print_box(box);
    if (!park_.given) {
      // Default: the back of the bed, centred on the print (background.md §1).
      c.park_x = has_box ? (box.min_x + box.max_x) / 2 : (park_.limits.bed.min_x + park_.limits.bed.max_x) / 2;
      c.park_y = park_.y;
    }
    // A park position needs no more than the slicer's 3 decimals.
    c.park_x = std::round(c.park_x * 1000) / 1000;
    c.park_y = std::round(c.park_y * 1000) / 1000;
    bool pushes = c.reload > 0 || c.purge > 0 || c.prime > 0;
    if (pushes && has_box && box.contains(c.park_x, c.park_y))
      throw InputError("line " + std::to_string(line) + ": the park position X" + num(c.park_x) + " Y" +
                       num(c.park_y) + " is above the print (X " + num(box.min_x) + ".." + num(box.max_x) + ", Y " +
                       num(box.min_y) + ".." + num(box.max_y) +
                       "): purging there would drop a blob on it; choose --park outside the print");
    c.message = expand(c.message, layer, z);
    c.host_message = expand(c.host_message, layer, z);
    c.before_wait = expand(c.before_wait, layer, z);
    c.after_wait = expand(c.after_wait, layer, z);
    c.custom_wait = expand(c.custom_wait, layer, z);
    gcode::PausePoint point{before, retraction_.pending(), top_z_};
    gcode::PauseBlock block;
    try {
      block = gcode::build_pause(point, c);
    } catch (const std::invalid_argument& e) {
      throw InputError("line " + std::to_string(line) + ": " + e.what());
    }
    std::string where = layer > 0 ? "before layer " + std::to_string(layer) : std::string("after the last layer");
    if (diag_.verbosity() > 0)
      diag_.info("pause " + where + " (Z " + num(z) + ") at line " + std::to_string(line));
    if (dry_run_) {
      out_.write((layer > 0 ? std::to_string(layer) : std::string("end")) + "\t" + num(z) + "\t" +
                 std::to_string(line) + "\tX" + num(c.park_x) + " Y" + num(c.park_y) + " Z" + num(block.park_z) +
                 "\n");
      return;
    }
    out_.write("; gc-pause-at: pause " + where + " (Z " + num(z) + ")");
    out_.write(ending_);
    for (const std::string& l : block.pause) {
      out_.write(l);
      out_.write(ending_);
    }
    out_.write("; gc-pause-at: resume");
    out_.write(ending_);
    for (const std::string& l : block.resume) {
      out_.write(l);
      out_.write(ending_);
    }
    out_.write("; gc-pause-at: end");
    out_.write(ending_);
  }

  gcode::OutputBuffer& out_;
  bool dry_run_;
  Where& where_;
  const Park& park_;
  const gcode::PauseConfig& config_;
  gcode::Diagnostics& diag_;
  gcode::RetractionTracker retraction_;
  gcode::Box2 box_;
  bool has_box_ = false;
  double top_z_ = 0;
  double top_layer_z_ = 0;
  int layers_ = 0;
  int pauses_ = 0;
  std::string ending_ = "\n";
};

// Lines read from a pipe before streaming starts, so the header's limits
// are known before the first byte goes out.
struct HeldHeader {
  std::string text;
  struct Item {
    std::size_t pos, len, ending;
    std::uint64_t number, offset;
  };
  std::vector<Item> items;
};

void check_where_results(const Where& w, const PauseWriter& writer) {
  int n = writer.layers();
  if (n == 0) throw InputError("no layers found: the input is empty or prints nothing");
  auto layers = [n] { return std::to_string(n) + (n == 1 ? " layer" : " layers"); };
  if (w.has_before && (w.before.highest_named() > n || w.fired_before == 0))
    throw InputError("--before-layer " + w.before.text() + ": no such layer, the file has " + layers());
  if (w.has_after && (w.after.highest_named() > n || w.fired_after == 0))
    throw InputError("--after-layer " + w.after.text() + ": no such layer, the file has " + layers());
  if (w.every > 0 && w.fired_every == 0)
    throw InputError("--every " + std::to_string(w.every) + ": the file has only " + layers() + ", so no pause");
  for (std::size_t i = 0; i < w.heights.size(); ++i)
    if (!w.height_used[i])
      throw InputError("--z " + num(w.heights[i]) + ": no layer starts above that height (the top layer is at Z " +
                       num(writer.top_layer_z()) + ")");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Insert a clean pause at layer boundaries: retract, lift, park at the back of the bed, wait,\n"
      "then heat, return to exactly where printing stopped and restore every mode.\n"
      "The pause goes after the last move of the previous layer and before the move to the\n"
      "next layer's Z. Several pauses may be given in one run.",
      kName};
  app.set_version_flag("--version", kVersion);
  app.get_formatter()->column_width(34);

  std::string input, output, before_layer, after_layer, heights_text, marker, bed, park_text, method_text = "M0";
  std::string before_text, after_text;
  bool in_place = false, dry_run = false, quiet = false, verbose = false, no_heat_wait = false;
  int every = 0;
  double max_z = 0, standby = 0;
  gcode::PauseConfig c;
  c.message = "Paused at layer {layer}";

  app.add_option("FILE", input, "Input G-code (default or '-': stdin)")->type_name("FILE");
  auto* o_out = app.add_option("-o,--output", output, "Write to FILE instead of stdout")->type_name("FILE");
  auto* o_inplace = app.add_flag("-i,--in-place", in_place, "Rewrite FILE in place (only when everything succeeded)");
  o_inplace->excludes(o_out);

  const char* where = "Where (at least one; they combine)";
  app.add_option("--before-layer", before_layer,
                 "Pause before these layers print (1 = first printed layer): 5, 5-9, 5,7,9-12")->type_name("RANGE")
      ->group(where);
  app.add_option("--after-layer", after_layer, "Pause once these layers are printed (N = before layer N+1)")->type_name("RANGE")
      ->group(where);
  app.add_option("--z", heights_text, "Pause before the first layer whose Z is above each height (mm, comma list)")->type_name("HEIGHTS")
      ->group(where);
  app.add_option("--every", every, "Pause every N layers (before layers N+1, 2N+1, ...)")->type_name("N")
      ->check(kPositive)
      ->group(where);
  app.add_option("--layer-marker", marker, "RE2 pattern of the layer comment, for files from other slicers")->type_name("REGEX")
      ->group(where);
  auto* o_dry = app.add_flag("--dry-run", dry_run, "List where each pause goes (layer, Z, line, park) and write no G-code")
                    ->group(where);
  o_dry->excludes(o_inplace);

  const char* printer = "Printer";
  app.add_option("--bed", bed, "Bed size WIDTHxDEPTH in mm (default: from the slicer's comments)")->type_name("WxD")->group(printer);
  app.add_option("--max-z", max_z, "Highest Z the printer reaches (default: from the slicer's comments; none)")->type_name("MM")
      ->check(kPositive)
      ->group(printer);
  app.add_option("--park", park_text, "Park position X,Y (default: X centre of the print, Y = bed depth - 10)")->type_name("X,Y")
      ->group(printer);
  app.add_option("--min-park-z", c.min_park_z, "Raise the head to at least this Z while parked (default: none)")->type_name("MM")
      ->check(kNonNegative)
      ->group(printer);

  const char* pause = "Pause";
  app.add_option("--method", method_text,
                 "Wait command: M0 M1 M25 M125 M226 M600 M601 @pause PAUSE G4 custom:'GCODE' none")->type_name("METHOD")
      ->capture_default_str()
      ->group(pause);
  auto* o_dwell = app.add_option("--dwell", c.dwell_seconds, "Seconds to wait with --method G4")->type_name("SECONDS")
                      ->capture_default_str()
                      ->check(kPositive)
                      ->group(pause);
  app.add_option("--retract", c.retract, "Retract mm before parking (0 = none; firmware G10 if the file uses it)")->type_name("MM")
      ->capture_default_str()
      ->check(kNonNegative)
      ->group(pause);
  app.add_option("--retract-speed", c.retract_speed, "Retract speed, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_option("--unretract-speed", c.unretract_speed, "Unretract speed, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_option("--lift", c.lift, "Lift mm above the highest printed Z (capped at --max-z)")->type_name("MM")
      ->capture_default_str()
      ->check(kNonNegative)
      ->group(pause);
  app.add_option("--z-speed", c.z_speed, "Z speed, mm/s")->type_name("MM/S")->capture_default_str()->check(kPositive)->group(pause);
  app.add_option("--travel-speed", c.travel_speed, "Travel speed to and from the park position, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_flag("--wait-moves", c.wait_for_moves, "Send M400 (finish moves) before the wait")->group(pause);
  auto* o_standby = app.add_option("--standby-temp", standby, "Hotend temperature while waiting (M104; default: unchanged)")->type_name("C")
                        ->check(kNonNegative)
                        ->group(pause);
  app.add_option("--resume-temp", c.resume_temp,
                 "Hotend temperature to resume at (default: the file's last M104/M109 target)")->type_name("C")
      ->check(kPositive)
      ->group(pause);
  app.add_flag("--no-heat-wait", no_heat_wait, "Resume with M104 (do not wait for the temperature) instead of M109")
      ->group(pause);
  app.add_option("--message", c.message,
                 "Text shown while paused (M0/M1 text, else M117); {layer} and {z} expand; '' = none")->type_name("TEXT")
      ->capture_default_str()
      ->group(pause);
  app.add_option("--host-message", c.host_message, "Text sent to the host with M118 (default: none)")->type_name("TEXT")->group(pause);
  app.add_flag("--beep", c.beep, "Beep (M300) when pausing")->group(pause);
  app.add_option("--beep-ms", c.beep_ms, "Beep length, ms")->type_name("MS")->capture_default_str()->check(kPositive)->group(pause);
  app.add_option("--beep-hz", c.beep_hz, "Beep pitch, Hz")->type_name("HZ")->capture_default_str()->check(kPositive)->group(pause);
  app.add_option("--stepper-hold", c.stepper_hold,
                 "Keep the steppers on for this many seconds while waiting (M84 S; default: firmware's)")->type_name("SECONDS")
      ->check(kPositive)
      ->group(pause);
  app.add_option("--unload", c.unload, "Unload this much filament at the park position before the wait (mm)")->type_name("MM")
      ->check(kNonNegative)
      ->group(pause);
  app.add_option("--unload-speed", c.unload_speed, "Unload speed, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_option("--reload", c.reload, "Load this much filament at the park position after the wait (mm)")->type_name("MM")
      ->check(kNonNegative)
      ->group(pause);
  app.add_option("--reload-speed", c.reload_speed, "Reload speed, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_option("--purge", c.purge, "Purge this much filament at the park position after the wait (mm)")->type_name("MM")
      ->check(kNonNegative)
      ->group(pause);
  app.add_option("--purge-speed", c.purge_speed, "Purge speed, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_option("--prime", c.prime, "Extra prime at the park position before returning (mm)")->type_name("MM")
      ->check(kNonNegative)
      ->group(pause);
  app.add_option("--prime-speed", c.prime_speed, "Prime speed, mm/s")->type_name("MM/S")
      ->capture_default_str()
      ->check(kPositive)
      ->group(pause);
  app.add_option("--before", before_text, "G-code (a file, or text with \\n between lines) just before the wait")->type_name("GCODE")
      ->group(pause);
  app.add_option("--after", after_text, "G-code (a file, or text with \\n between lines) just after the wait")->type_name("GCODE")
      ->group(pause);

  app.add_flag("-q,--quiet", quiet, "Only errors");
  app.add_flag("-v,--verbose", verbose, "Report each pause on stderr");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s\n", kName, e.what());
    return 2;
  }

  return gcode::run_tool(kName, [&]() -> int {
    Where w;
    std::string custom;
    try {
      if (in_place && (input.empty() || input == "-")) throw UsageError("-i needs a FILE, not stdin");
      if (!before_layer.empty()) {
        w.has_before = true;
        w.before = gcode::LayerRange::parse(before_layer);
      }
      if (!after_layer.empty()) {
        w.has_after = true;
        w.after = gcode::LayerRange::parse(after_layer);
      }
      if ((w.has_before && w.before.needs_total()) || (w.has_after && w.after.needs_total()))
        throw UsageError("layers counted from the end ('-N') are not known while streaming; name them");
      if (!heights_text.empty()) {
        w.heights = parse_numbers(heights_text, "--z");
        std::sort(w.heights.begin(), w.heights.end());
        w.height_used.assign(w.heights.size(), false);
      }
      w.every = every;
      if (!w.has_before && !w.has_after && w.heights.empty() && w.every == 0)
        throw UsageError("nothing to do: give --before-layer, --after-layer, --z or --every");
      if (!gcode::parse_pause_method(method_text, c.method, custom))
        throw UsageError("--method: unknown '" + method_text +
                         "' (M0 M1 M25 M125 M226 M600 M601 @pause PAUSE G4 custom:'...' none)");
      if (c.method == gcode::PauseMethod::Custom) c.custom_wait = gcode_text(custom);
      if (o_dwell->count() > 0 && c.method != gcode::PauseMethod::Dwell)
        throw UsageError("--dwell goes with --method G4");
      if (no_heat_wait && o_standby->count() == 0) throw UsageError("--no-heat-wait goes with --standby-temp");
      if (max_z > 0 && c.min_park_z > max_z) throw UsageError("--min-park-z is above --max-z");
    } catch (const UsageError& e) {
      std::fprintf(stderr, "%s: %s\n", kName, e.what());
      return 2;
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "%s: %s\n", kName, e.what());
      return 2;
    }
    c.standby = o_standby->count() > 0;
    c.standby_temp = standby;
    c.wait_for_heat = !no_heat_wait;
    c.before_wait = before_text.empty() ? std::string() : gcode_text(before_text);
    c.after_wait = after_text.empty() ? std::string() : gcode_text(after_text);

    gcode::Diagnostics diag(kName, quiet ? -1 : (verbose ? 1 : 0));
    gcode::LayerMarkers markers = marker.empty() ? gcode::LayerMarkers() : gcode::LayerMarkers(marker);
    gcode::InputFile in(input);
    gcode::LineReader reader(in.fd());

    // Printer limits: a regular file is read ahead (Prusa writes its config
    // at the end); a pipe is only looked at up to its first move.
    Park park;
    HeldHeader held;
    if (!gcode::scan_file_limits(in.fd(), park.limits)) {
      gcode::RawLine raw;
      while (held.text.size() < (1u << 20) && reader.next(raw)) {
        held.items.push_back({held.text.size(), raw.text.size(), raw.ending.size(), raw.number, raw.offset});
        held.text.append(raw.text);
        held.text.append(raw.ending);
        if (gcode::Line::parse(raw.text).is_move()) break;
      }
      park.limits = gcode::scan_text_limits(held.text);
    }
    try {
      if (!bed.empty()) {
        park.limits.has_bed = true;
        park.limits.bed = parse_bed(bed);
      }
      if (!park_text.empty()) {
        std::vector<double> xy = parse_numbers(park_text, "--park");
        if (xy.size() != 2) throw UsageError("--park: give X,Y (e.g. 110,210)");
        park.given = true;
        park.x = xy[0];
        park.y = xy[1];
      }
    } catch (const UsageError& e) {
      std::fprintf(stderr, "%s: %s\n", kName, e.what());
      return 2;
    }
    if (max_z > 0) {
      park.limits.has_max_z = true;
      park.limits.max_z = max_z;
    }
    if (park.limits.has_max_z) {
      c.max_z = park.limits.max_z;
      if (c.min_park_z > c.max_z)
        throw InputError("--min-park-z " + num(c.min_park_z) + " is above the printer's height " + num(c.max_z));
    }
    if (park.given) {
      c.park_x = park.x;
      c.park_y = park.y;
    } else if (park.limits.has_bed) {
      park.from_bed = true;
      park.y = park.limits.bed.max_y - 10;
    } else {
      throw InputError("the file does not say how big the bed is, so the park position is unknown: "
                       "give --park X,Y (or --bed WIDTHxDEPTH)");
    }
    // Cura writes the print's height in its header: a height above it can
    // be refused before anything is written.
    if (park.limits.has_print_top)
      for (double h : w.heights)
        if (h >= park.limits.print_top)
          throw InputError("--z " + num(h) + ": the print is only " + num(park.limits.print_top) + " mm high");

    gcode::OutputFile out_file(dry_run ? output : (in_place ? std::string() : output), in_place ? input : std::string());
    {
      gcode::OutputBuffer out(out_file.fd());
      PauseWriter writer(out, dry_run, w, park, c, diag);
      gcode::LayerTracker tracker(writer, markers);
      for (const HeldHeader::Item& it : held.items) {
        gcode::RawLine raw;
        raw.text = std::string_view(held.text).substr(it.pos, it.len);
        raw.ending = std::string_view(held.text).substr(it.pos + it.len, it.ending);
        raw.number = it.number;
        raw.offset = it.offset;
        tracker.push(raw);
      }
      gcode::RawLine raw;
      while (reader.next(raw)) tracker.push(raw);
      tracker.finish();
      check_where_results(w, writer);
      out.flush();
    }
    out_file.commit();
    return 0;
  });
}
