#pragma once
// STL, binary and ASCII, into a welded Mesh (mesh.hpp).
//
// Which of the two a file is, is told by its size, not by its first word:
// a binary file is 84 + 50 n bytes for the n triangles its header counts,
// and its 80-byte header may well begin with "solid" (many exporters write
// that). Anything else that begins with "solid" and holds no NUL byte in
// its first kilobyte is read as ASCII.
// The normals are skipped (the corners alone define a triangle; exporters
// write them flipped or zero). Refused with a MeshError that says where:
// a binary file whose size does not match its count (truncated, or not an
// STL), an ASCII facet that is not three vertices, a coordinate that is not
// a finite number, a file with no triangle left after welding.
#include <string_view>

#include "gcode/procedural/mesh.hpp"

namespace gcode::procedural {

// Corners closer than this (mm, in the file's units) become one vertex.
inline constexpr double kStlMergeDistance = 1e-3;

// `name` is the file's name for the messages.
Mesh read_stl(std::string_view bytes, std::string_view name, double merge_distance = kStlMergeDistance);

}  // namespace gcode::procedural
