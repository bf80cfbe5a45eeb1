#include "gcode/procedural/wall_outline.hpp"

#include <fmt/format.h>

#include <cmath>

#include "gcode/core/number.hpp"
#include "gcode/procedural/outline_offset.hpp"

namespace gcode::procedural {

namespace {

// Whether `p` is inside `loop` (crossings of a ray to +X).
bool inside(const Point2& p, const Polygon& loop) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Point2& a = loop[i];
    const Point2& b = loop[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)) in = !in;
  }
  return in;
}

}  // namespace

WallOutline wall_outline(const MeshSection& section, double line_width, double tolerance) {
  if (section.open_ends > 0)
    return {{}, "the section does not close (the mesh has a hole there)"};
  if (section.crowded_edges > 0)
    return {{}, "edges are shared by more than two triangles (the mesh is not a closed surface)"};
  if (section.loops.empty()) return {{}, "the mesh has no section"};
  std::size_t outer = 0;
  for (std::size_t i = 1; i < section.loops.size(); ++i)
    if (std::fabs(loop_area(section.loops[i])) > std::fabs(loop_area(section.loops[outer]))) outer = i;
  int islands = 1;
  for (std::size_t i = 0; i < section.loops.size(); ++i)
    if (i != outer && !inside(section.loops[i][0], section.loops[outer])) ++islands;
  if (islands > 1) return {{}, fmt::format("the section splits into {} islands (a vase has one wall)", islands)};
  const Polygon thin = simplify_loop(section.loops[outer], tolerance / 4);
  std::vector<Polygon> pieces = offset_inward(thin, line_width / 2, tolerance / 2);
  if (pieces.empty()) return {{}, "the section is narrower than a line width"};
  if (pieces.size() > 1)
    return {{}, fmt::format("the bead's line splits into {} pieces (a neck narrower than a line width)", pieces.size())};
  return {std::move(pieces[0]), ""};
}

void HeightProblems::add(const std::string& problem, double z) {
  for (Kind& k : kinds_)
    if (k.problem == problem) {
      k.last = z;
      ++k.count;
      return;
    }
  kinds_.push_back({problem, z, z, 1});
}

std::string HeightProblems::message() const {
  std::string m;
  for (const Kind& k : kinds_) {
    if (!m.empty()) m += "; ";
    m += k.count == 1 ? fmt::format("{} at z = {} mm", k.problem, number_string(k.first, 3))
                      : fmt::format("{} at z = {} .. {} mm ({} heights)", k.problem, number_string(k.first, 3),
                                    number_string(k.last, 3), k.count);
  }
  return m;
}

}  // namespace gcode::procedural
