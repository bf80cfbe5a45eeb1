#include "test_support.hpp"

#include "gcode/core/output_buffer.hpp"
#include "gcode/pipeline/writer.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "gcode/core/e_mode.hpp"
#include "gcode/core/line.hpp"
#include "gcode/core/line_reader.hpp"

namespace gctest {

namespace fs = std::filesystem;

std::string fixture_path(std::string_view name) { return std::string(GC_FIXTURES_DIR) + "/" + std::string(name); }
std::string tool_path(std::string_view tool) { return std::string(GC_TOOLS_DIR) + "/" + std::string(tool); }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const std::string& path, std::string_view data) {
  std::ofstream out(path, std::ios::binary);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string head_of(const std::string& name, std::size_t lines) {
  std::string text = read_file(fixture_path(name));
  std::size_t pos = 0;
  for (std::size_t i = 0; i < lines && pos != std::string::npos; ++i) pos = text.find('\n', pos + 1);
  return pos == std::string::npos ? text : text.substr(0, pos + 1);
}

std::vector<std::string> fixture_names() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(GC_FIXTURES_DIR))
    if (e.path().extension() == ".gcode") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

nlohmann::json expected_data(std::string_view fixture) {
  std::string stem(fixture.substr(0, fixture.rfind(".gcode")));
  fs::path path = fs::path(GC_FIXTURES_DIR) / "expected" / (stem + ".json");
  if (!fs::exists(path)) return nullptr;
  return nlohmann::json::parse(read_file(path.string()));
}

namespace {

// The scratch folders of this test process, removed when it exits (a run of
// the suite made some 7,000 of them, 2 GB, and left them all in /tmp).
// GCTEST_KEEP_TEMP=1 keeps them, to look at a failing test's files.
class TempDirs {
 public:
  ~TempDirs() {
    if (std::getenv("GCTEST_KEEP_TEMP") != nullptr) return;
    std::error_code ignored;
    for (const fs::path& p : made_) fs::remove_all(p, ignored);
  }
  void add(const fs::path& p) {
    const std::lock_guard<std::mutex> lock(mutex_);
    made_.push_back(p);
  }

 private:
  std::mutex mutex_;
  std::vector<fs::path> made_;
};

}  // namespace

std::string temp_dir() {
  static std::atomic<int> counter{0};
  static TempDirs made;
  fs::path p = fs::temp_directory_path() /
               ("gctest-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  made.add(p);
  return p.string();
}

std::string quote(std::string_view arg) {
  std::string q = "'";
  for (char c : arg) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

std::string wait_until(const std::string& condition, int tries, double pause) {
  return fmt::format("for i in $(seq {}); do {} && break; sleep {:g}; done\n", tries, condition, pause);
}

std::string wait_for_lines(const std::string& file, const LinesWait& wait) {
  std::string line = quote(tool_path("gctest-wait"));
  auto option = [&line](const char* name, const std::string& word) {
    if (!word.empty()) line += fmt::format(" {} {}", name, word);
  };
  option("--match", wait.match);
  option("--after", wait.after);
  option("--at-least", wait.at_least);
  option("--while-alive", wait.while_alive);
  return line + fmt::format(" --tries {} --every {:g} {} || :\n", wait.tries, wait.every, file);
}

std::string numbered_log_line() { return quote("^[^\t]*\t[0-9]"); }

std::string numbered_log_count(const std::string& log) { return "grep -c " + numbered_log_line() + " " + quote(log); }

std::string wait_for_journal_start(const std::string& journal, const std::string& while_alive) {
  return wait_for_lines(quote(journal), {.match = "'^A '", .while_alive = while_alive, .tries = 5000, .every = 0.002});
}

std::string wait_for_fifo(const std::string& path) { return wait_until("[ -p " + quote(path) + " ]"); }

std::string wait_for_link(const std::string& path) { return wait_until("[ -e " + quote(path) + " ]", 500); }

std::string tool_command(std::string_view tool, const std::string& args) {
  return quote(tool_path(tool)) + " " + args;
}

namespace {

// gc-send's default journal is per port name, and every pty test's port is
// named "printer": tests running side by side would share one journal in
// the user's state folder, which gc-send's lock refuses. Each test process
// has a state folder of its own (a script may still set its own).
void own_state_folder() {
  static const std::string state = [] {
    std::string folder = temp_dir() + "/state";
    ::setenv("XDG_STATE_HOME", folder.c_str(), 1);
    return folder;
  }();
}

}  // namespace

RunResult run(const std::string& command_line, std::string_view input) {
  own_state_folder();
  std::string dir = temp_dir();
  std::string in_path = dir + "/stdin", out_path = dir + "/stdout", err_path = dir + "/stderr";
  write_file(in_path, input);
  std::string full = "(" + command_line + ") <" + quote(in_path) + " >" + quote(out_path) + " 2>" + quote(err_path);
  int raw = std::system(full.c_str());
  RunResult r;
  if (WIFEXITED(raw)) {
    r.status = WEXITSTATUS(raw);
  } else if (WIFSIGNALED(raw)) {
    r.status = 128 + WTERMSIG(raw);
  }
  r.out = read_file(out_path);
  r.err = read_file(err_path);
  fs::remove_all(dir);
  return r;
}

OpenedFile::OpenedFile(const std::string& path) : fd_(::open(path.c_str(), O_RDONLY)) {
  if (fd_ < 0) throw std::runtime_error("cannot open " + path);
}

OpenedFile::~OpenedFile() { ::close(fd_); }

std::set<std::string> long_options(std::string text) {
  for (std::size_t p; (p = text.find("\\-")) != std::string::npos;) text.erase(p, 1);
  std::set<std::string> names;
  for (std::size_t p = 0; (p = text.find("--", p)) != std::string::npos;) {
    std::size_t e = p + 2;
    while (e < text.size() && ((text[e] >= 'a' && text[e] <= 'z') || (text[e] >= '0' && text[e] <= '9') ||
                               (text[e] == '-' && e > p + 2)))
      ++e;
    if (e > p + 3) names.insert(text.substr(p, e - p));
    p = e;
  }
  return names;
}

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) lines.emplace_back(std::string(raw.text) + std::string(raw.ending));
  return lines;
}

gcode::MachineState initial_state(std::string_view text) {
  gcode::MachineState state;
  std::size_t tail = text.size() > (1u << 16) ? text.size() - (1u << 16) : 0;
  gcode::EModeGuess g = gcode::guess_e_mode(text.substr(0, std::min<std::size_t>(text.size(), 1u << 20)), text.substr(tail));
  if (!g.file_sets_mode && g.guessed) {
    state.relative_e = g.relative;
    state.e_follows_g90 = false;
  }
  return state;
}

std::string without_e_mode_warning(const std::string& err) {
  std::string out;
  for (const std::string& l : split_lines(err))
    if (l.find("never sets the E mode (M82/M83)") == std::string::npos) out += l;
  return out;
}

std::vector<ReplayedMove> replay_moves(std::string_view text) {
  std::vector<ReplayedMove> moves;
  gcode::MachineState state = initial_state(text);
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  std::size_t index = 0;
  while (split.next(raw)) {
    gcode::Line line = gcode::Line::parse(raw.text);
    gcode::Move m = state.apply(line);
    if (m.kind == gcode::MoveKind::Linear || m.kind == gcode::MoveKind::Arc) moves.push_back({m, state, index});
    ++index;
  }
  return moves;
}

int e_mode_commands(std::string_view text) {
  int n = 0;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) {
    gcode::Line line = gcode::Line::parse(raw.text);
    n += line.is_m(82) || line.is_m(83) ? 1 : 0;
  }
  return n;
}

gcode::MachineState replay_state(std::string_view text) {
  gcode::MachineState state = initial_state(text);
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) state.apply(gcode::Line::parse(raw.text));
  return state;
}

LinePlace places_of(const std::string& text) {
  struct Sink : gcode::LayerSink {
    LinePlace p;
    gcode::LayerTracker* tracker = nullptr;
    double z = 0;
    void on_layer(const gcode::LayerInfo& l, const gcode::MachineState&) override { z = l.z; }
    void on_line(const gcode::TrackedLine& t) override {
      p.layer.push_back(t.region == gcode::Region::Layer ? t.layer : 0);
      p.feature.push_back(t.feature >= 0 ? tracker->feature_name(t.feature) : std::string());
      p.layer_z.push_back(z);
    }
  } sink;
  gcode::LayerMarkers markers;
  gcode::LayerTracker tracker(sink, markers);
  sink.tracker = &tracker;
  gcode::MemoryLineSplitter split(text);
  gcode::RawLine raw;
  while (split.next(raw)) tracker.push(raw);
  tracker.finish();
  return sink.p;
}

std::string run_stages(gcode::Pipeline& pipeline, std::string_view text) {
  std::string out;
  {
    gcode::OutputBuffer buffer(out);
    gcode::GcodeWriter writer(buffer);
    pipeline.add(writer);
    pipeline.run_text(text);
  }
  return out;
}

std::string run_stages(std::string_view text, std::initializer_list<gcode::Stage*> stages, bool layers) {
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = layers});
  for (gcode::Stage* s : stages) pipeline.add(*s);
  return run_stages(pipeline, text);
}

Subdivided subdivide(std::string_view text, const gcode::SubdivideOptions& options,
                     gcode::Diagnostics* diagnostics) {
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers, gcode::PipelineOptions{.layers = false});
  gcode::Subdivider subdivider(options, pipeline.precision(), diagnostics);
  pipeline.add(subdivider);
  std::string out = run_stages(pipeline, text);
  return {std::move(out), subdivider.stats()};
}

std::string subdivided(std::string_view text, double max_length) {
  gcode::SubdivideOptions options;
  options.max_length = max_length;
  return subdivide(text, options).text;
}

}  // namespace gctest
