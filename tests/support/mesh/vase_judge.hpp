#pragma once
// What a VaseCheck (vase_check.hpp) must show, as Catch2 checks: the wall
// inside its sections and half a line width from them within 0.03 mm, Z
// never falling, nothing but beads, the filament of the bead within 2 %,
// the top reached; the bottom near every point of the first section.
#include <catch2/catch.hpp>

#include "vase_check.hpp"

namespace meshtest {

inline void judge_wall(const VaseCheck& c) {
  INFO("worst offset " << c.worst_offset << " at " << c.worst_at[0] << "," << c.worst_at[1] << "," << c.worst_at[2]
                       << ", flow " << c.worst_flow << ", outside " << c.outside << "/"
                       << c.wall_samples);
  CHECK(c.wall_samples > 1000);
  CHECK(c.outside == 0);
  CHECK(c.worst_offset <= 0.03);
  CHECK(c.z_fall <= 0);
  CHECK(c.other_moves == 0);
  CHECK(c.worst_flow <= 0.02);
  CHECK(c.wall_top == Approx(c.model_top).margin(0.001));
}

inline void judge_bottom(const VaseCheck& c) {
  INFO("gap " << c.bottom_gap << ", far " << c.bottom_far);
  CHECK(c.bottom_points > 100);
  CHECK(c.bottom_gap <= 0.5);
  CHECK(c.bottom_far <= 0.05);
}

}  // namespace meshtest
