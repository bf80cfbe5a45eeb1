#include "gcode/cli/filter.hpp"

namespace gcode::cli {

int count_layers(int fd, const LayerMarkers& markers) {
  Pipeline counting(markers);
  counting.run(fd);
  return counting.tracker().layer_count();
}

Filter::Filter(const FilterOptions& options, PipelineOptions pipeline)
    : options_(options), markers_(options.markers()), input_(options.file), pipeline_(markers_, pipeline) {}

int Filter::count_layers() {
  input_.make_seekable();
  int layers = cli::count_layers(input_.fd(), markers_);
  input_.rewind();
  return layers;
}

LayerSelection Filter::selection(const SelectionText& text) {
  LayerSelection s;
  try {
    s = LayerSelection::parse(text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (s.needs_total()) s.set_total(count_layers());
  s.bind(pipeline_.tracker());
  return s;
}

PrintArea Filter::print_area() {
  PrintArea area;
  if (scan_file_limits(input_.fd(), area)) return area;
  return scan_text_limits(pipeline_.read_header(input_.fd()));
}

void Filter::write(const std::function<void()>& verify) {
  file_.emplace(options_.in_place ? std::string() : options_.output, options_.in_place ? options_.file : std::string());
  buffer_.emplace(file_->fd());
  writer_.emplace(*buffer_);
  pipeline_.add(*writer_);
  if (done_) {
    while (!done_() && pipeline_.read_some(input_.fd())) {
    }
    pipeline_.finish();
  } else {
    pipeline_.run(input_.fd());
  }
  buffer_->flush();
  if (verify) verify();
  file_->commit();
}

}  // namespace gcode::cli
