#pragma once
// What a ;TYPE: comment names, across slicers.
//
// Each slicer spells the same feature its own way: Cura's WALL-OUTER is
// PrusaSlicer's "External perimeter" and Orca's "Outer wall". A user who
// asks for one spelling means the feature, so names are compared by kind
// first (case-insensitive), then by exact name for kinds this table does not
// know (a slicer's own feature names still work, matched case-insensitively).
#include <cstdint>
#include <string_view>

namespace gcode {

enum class FeatureKind : std::uint8_t {
  Unknown,
  OuterWall,         // WALL-OUTER, External perimeter, Outer wall
  InnerWall,         // WALL-INNER, Perimeter, Inner wall
  OverhangWall,      // Overhang perimeter, Overhang wall
  Infill,            // FILL, Internal infill, Sparse infill
  SolidInfill,       // SKIN, Solid infill, Internal solid infill
  TopSurface,        // Top solid infill, Top surface
  BottomSurface,     // Bottom surface
  Bridge,            // Bridge infill, Internal bridge
  GapFill,           // Gap fill
  Support,           // SUPPORT, Support material
  SupportInterface,  // SUPPORT-INTERFACE, Support material interface
  Skirt,             // SKIRT, Skirt/Brim, Skirt, Brim
  PrimeTower,        // PRIME-TOWER, Wipe tower, Prime tower
  Ironing,           // Ironing
  Custom,            // Custom (start/end code of PrusaSlicer)
};

// The kind a slicer's feature name stands for (Unknown when not in the table).
FeatureKind feature_kind(std::string_view name);
// Whether a name the user gave selects a feature named `name` in the file.
bool feature_matches(std::string_view wanted, std::string_view name);
// Case-insensitive ASCII comparison.
bool same_name(std::string_view a, std::string_view b);

}  // namespace gcode
