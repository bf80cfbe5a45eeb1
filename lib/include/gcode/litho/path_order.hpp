#pragma once
// The printing order of a lithophane layer's paths and the travel between
// them, so that the head travels little and never leaves the part.
//
// The planner (lithophane.hpp) makes each layer's paths in a fixed order:
// walls starting at the left end (flat) or at s = 0 (cylinder), then the
// passes group by group along s. Printed like that, every layer ends where
// its last pass ends and the next one begins far away, and the passes of a
// group that ends on the wrong side cost a travel across the group.
// order_layer instead:
//   - starts the walls at the point of their loop (flat: inner wall, cap,
//     outer wall, cap; cylinder: each ring) nearest to the head, cutting a
//     piece in two there, so a layer begins right above where the last one
//     ended;
//   - then orders the passes for the least travel: seen along the base the
//     runs are edges between the positions of their ends, and a walk through
//     all of them from the head needs travel only to pair up the positions
//     with an odd count of run ends (the head's counted once more) but one,
//     where the walk ends; neighbours along the base are paired (cheapest on
//     a line or circle), parts left apart are joined there and back, and the
//     walk is an Euler path. Nearest first (from each of the eight nearest
//     runs) and group by group along the base are tried as well; the least
//     travel, estimated along the base, wins;
//   - routes each travel inside the layer's band (a "combed" travel, as
//     slicers do): straight where the straight line stays inside, else
//     across to the middle of the band's thinnest part on the way, along it,
//     and back out; such a travel runs over the part and needs no retraction.
// The paths' pieces are not changed, only cut at the start point, reversed
// or rotated, so volumes, widths and speeds are the planner's.
#include "gcode/litho/lithophane.hpp"

namespace gcode::litho {

// Reorders `layer` (planned by `planner`) for a head standing at `from`.
void order_layer(const LithophanePlanner& planner, LithoLayer& layer, Point from);

// Plans layer `index` and orders it for the head at `head`, then moves
// `head` to where the layer ends: what a writer calls layer after layer. For
// layer 0, `head` = the planner's own first start (no reordering of walls).
void plan_ordered_layer(const LithophanePlanner& planner, int index, LithoLayer& out, Point& head);

}  // namespace gcode::litho
