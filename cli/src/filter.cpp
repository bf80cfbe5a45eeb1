#include "gcode/cli/filter.hpp"

#include <cstdio>
#include <stdexcept>

#include "gcode/core/e_mode.hpp"
#include "gcode/core/feature.hpp"

namespace gcode::cli {

int count_layers(int fd, const LayerMarkers& markers, int e_relative) {
  Pipeline counting(markers);
  if (e_relative == 0 || e_relative == 1) counting.set_e_mode(e_relative == 1);
  counting.run(fd);
  return counting.tracker().layer_count();
}

Filter::Filter(const FilterOptions& options, PipelineOptions pipeline)
    : options_(options), markers_(options.markers()), input_(options.file), pipeline_(markers_, pipeline) {
  input_.widen_pipe();
}

bool Filter::e_mode() {
  if (e_relative_ >= 0) return e_relative_ == 1;
  EModeChoice choice = EModeChoice::Auto;
  parse_e_mode(options_.e_mode, choice);
  EModeReading reading =
      read_e_mode_of(input_.fd(), choice, input_.name(), [&] { return pipeline_.read_ahead(input_.fd(), 1 << 20); });
  if (reading.file_sets_mode) {
    e_relative_ = 2;
    return false;
  }
  bool relative = reading.relative;
  if (!reading.warning.empty() && options_.verbosity() >= 0)
    std::fprintf(stderr, "%s: warning: %s\n", options_.tool.c_str(), reading.warning.c_str());
  e_relative_ = relative ? 1 : 0;
  pipeline_.set_e_mode(relative);
  return relative;
}

int Filter::count_layers() {
  // A pipe is kept in a temp file first: nothing may have been read ahead
  // into the pipeline yet (the E mode is guessed from the file afterwards).
  if (!pipeline_.buffered().empty()) throw std::logic_error("Filter::count_layers after reading ahead");
  input_.make_seekable();
  e_mode();
  int layers = cli::count_layers(input_.fd(), markers_, e_relative_);
  input_.rewind();
  return layers;
}

namespace {

// Keeps every layer event of a reading.
class LayerLister : public Stage {
 public:
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override {
    layers.push_back(info);
    out.layer(info, before);
  }
  bool reads_state() const override { return false; }
  bool reads_lines() const override { return false; }
  std::vector<LayerInfo> layers;
};

}  // namespace

const InputScan& Filter::scan() {
  if (scanned_) return *scanned_;
  input_.make_seekable();
  LayerLister lister;
  Pipeline reading(markers_);
  reading.add(lister);
  reading.run(input_.fd());
  input_.rewind();
  InputScan& found = scanned_.emplace();
  found.layers = std::move(lister.layers);
  for (int f = 0; f < reading.tracker().feature_count(); ++f) found.features.push_back(reading.tracker().feature_name(f));
  return found;
}

void Filter::prepass(Stage& stage, const std::function<void(const Pipeline&)>& after) {
  if (!pipeline_.buffered().empty()) throw std::logic_error("Filter::prepass after reading ahead");
  input_.make_seekable();
  e_mode();
  Pipeline reading(markers_);
  if (e_relative_ == 0 || e_relative_ == 1) reading.set_e_mode(e_relative_ == 1);
  reading.add(stage);
  reading.run(input_.fd());
  if (after) after(reading);
  input_.rewind();
}

LayerSelection Filter::selection(const SelectionText& text) {
  LayerSelection s;
  try {
    s = LayerSelection::parse(text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  // --types names the file must have: checked before a byte goes out, or a
  // wrong name would first copy the whole file to standard output and only
  // then fail. One extra read of the input, for this option only.
  if (!s.types().empty()) check_types(s.types(), scan().features);
  if (s.needs_total()) s.set_total(count_layers());
  s.bind(pipeline_.tracker());
  return s;
}

void check_types(const std::vector<std::string>& wanted, const std::vector<std::string>& features) {
  std::string unknown;
  for (const std::string& w : wanted) {
    bool found = false;
    for (const std::string& f : features) found = found || feature_matches(w, f);
    if (!found) unknown += (unknown.empty() ? "'" : ", '") + w + "'";
  }
  if (unknown.empty()) return;
  if (features.empty()) throw UsageError("--types " + unknown + ": the file has no ;TYPE: comments");
  std::string names;
  for (const std::string& f : features) names += (names.empty() ? "'" : ", '") + f + "'";
  throw UsageError("--types: no feature " + unknown + " in the file; it has " + names);
}

void Filter::check_selection(const LayerSelection& where, Diagnostics& diag, std::string_view done) {
  // --types names were checked by selection(), before any output.
  if (where.by_layer() && where.layers_selected() == 0)
    diag.warn("no layer of " + input_.name() + " matches the selection; nothing was " + std::string(done));
}

PrintArea Filter::print_area() {
  PrintArea area = slicer_environment(), file;
  if (!scan_file_limits(input_.fd(), file)) file = scan_text_limits(pipeline_.read_header(input_.fd()));
  area.merge(file);
  return area;
}

void write_output_file(const std::string& path, const std::function<void(OutputBuffer&)>& fill) {
  OutputFile file(path, std::string());
  OutputBuffer buffer(file.fd());
  fill(buffer);
  buffer.flush();
  file.commit();
}

void Filter::run() {
  e_mode();
  pipeline_.run(input_.fd());
}

void Filter::write(const std::function<void()>& verify) {
  e_mode();
  file_.emplace(options_.in_place ? std::string() : options_.output, options_.in_place ? options_.file : std::string());
  file_->widen_pipe();
  buffer_.emplace(file_->fd());
  writer_.emplace(*buffer_);
  pipeline_.add(*writer_);
  if (done_) {
    while (!done_() && pipeline_.read_some(input_.fd())) {
    }
    pipeline_.finish_early();  // a no-op when the input ended
  } else {
    pipeline_.run(input_.fd());
  }
  buffer_->flush();
  if (verify) verify();
  file_->commit();
}

}  // namespace gcode::cli
