// gc-shape: printable primitives without a slicer, each one seamless path
// (background.md §2). The geometry and the G-code are the library's
// (procedural/shape.hpp, procedural/shape_gcode.hpp).
#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <optional>

#include "gcode/core/file_io.hpp"
#include "gcode/cli/shape_options.hpp"
#include "gcode/cli/tool.hpp"
#include "gcode/core/output_buffer.hpp"
#include "gcode/procedural/mesh_vase.hpp"
#include "gcode/procedural/shape_gcode.hpp"
#include "gcode/procedural/stl_reader.hpp"

namespace {

namespace procedural = gcode::procedural;

using Options = gcode::cli::ShapeToolOptions;

// A regular file in one read (a mesh may be 50 MB: a stream copied byte by byte took a tenth of a run);
// a pipe, whose size is unknown, through the stream.
std::string text_of(const std::string& path, const char* option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw gcode::cli::InputError(fmt::format("{} {}: cannot open it", option, path));
  const std::streamoff size = in.seekg(0, std::ios::end) ? static_cast<std::streamoff>(in.tellg()) : -1;
  in.clear();
  if (size < 0) return {std::istreambuf_iterator<char>(in), {}};
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(text.data(), size)) throw gcode::cli::InputError(fmt::format("{} {}: cannot read it", option, path));
  return text;
}

procedural::ShapePath path_of(const Options& o) {
  if (o.mesh.empty()) return procedural::ShapePath(o.shape);
  procedural::Mesh mesh = procedural::read_stl(text_of(o.mesh, "--mesh"), o.mesh);  // the file's bytes freed here
  return procedural::mesh_vase(std::move(mesh), o.shape, o.mesh);
}

int write(Options& o, gcode::cli::Tool& tool) {
  gcode::Diagnostics diag = tool.diagnostics(o.io);
  if (!o.start.empty()) o.gcode.start_code = text_of(o.gcode.start_name = o.start, "--start");
  if (!o.end.empty()) o.gcode.end_code = text_of(o.gcode.end_name = o.end, "--end");
  const procedural::ShapePath path = path_of(o);
  gcode::OutputFile file(o.io.output, "");
  file.widen_pipe();  // gc-shape | gc-deform
  std::optional<gcode::OutputBuffer> out(file.fd());
  const procedural::ShapeGcodeStats stats =
      procedural::write_shape_gcode(path, o.gcode, [&](std::string_view chunk) { out->write(chunk); });
  out->flush();
  file.commit();
  diag.info(fmt::format("{}: {} layers, {} moves, {:.2f} m of path, {:.3f} m of filament", o.kind, stats.layers,
                        stats.moves, stats.length / 1000, stats.filament / 1000));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  gcode::cli::Tool tool(
      "gc-shape",
      "gc-shape: primitives printed without a slicer, each one seamless path; a rising spiral has no seam and no\n"
      "layer change (one turn = one layer). Diameters are the path's centre line.\n"
      "  gc-shape helix --diameter 60 --height 80 > cup.gcode\n"
      "  gc-shape cylinder --diameter 40 --height 30 | gc-deform --cylinder 'r + 1.05*z' theta '0.3*z' > dish.gcode\n"
      "  gc-shape vase --mesh shade.stl --bottom-layers 3 > shade.gcode");
  gcode::cli::add_shape_options(tool, o);
  return tool.run(argc, argv, [&] { return write(o, tool); });
}
