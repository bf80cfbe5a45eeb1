#pragma once
// The lithophane as a binary STL, to slice it conventionally and compare.
//
// Physics in two sentences: a slicer fills the solid with ordinary infill
// lines at a fixed width and a fixed speed, so the extruder rate changes with
// every change of line and the thin gaps get voids; the variable-width passes
// keep the rate and fill the gap exactly. For a fair comparison both start
// from the same solid: this mesh is the HeightMap sampled on a grid of
// `resolution` mm, the same placement on the bed as the G-code.
//
// The mesh is closed and consistently oriented (every edge is shared by
// exactly two triangles that run it in opposite directions; normals point
// out): flat = picture face, base face, four sides; cylinder = outer and
// inner surfaces, top and bottom rings. Triangles are streamed one grid row
// at a time, so memory is two rows of samples.
#include <cstdint>
#include <functional>
#include <string_view>

#include "gcode/litho/height_map.hpp"

namespace gcode::litho {

struct StlOptions {
  double resolution = 0.2;   // mm between grid points along the base and up
  double center_x = 110;     // mm: the same placement as LithoOptions
  double center_y = 110;
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct StlStats {
  std::uint32_t triangles = 0;
  std::uint64_t bytes = 0;
};

using BytesOut = std::function<void(std::string_view)>;

// Triangles the mesh will have; throws std::invalid_argument past 2^32 - 1
// (the STL count field), which only an absurdly fine resolution reaches.
std::uint32_t litho_stl_triangles(const HeightMap& map, const StlOptions& options);

// Writes the binary STL (80-byte header, count, 50 bytes a triangle).
StlStats write_litho_stl(const HeightMap& map, const StlOptions& options, const BytesOut& out);

}  // namespace gcode::litho
