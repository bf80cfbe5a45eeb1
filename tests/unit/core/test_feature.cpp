// ;TYPE: names across slicers (core/feature.hpp): one kind for each
// spelling, compared case-insensitively; names the table does not know still
// match themselves, and never each other.
#include <catch2/catch.hpp>

#include "gcode/core/feature.hpp"

using gcode::feature_kind;
using gcode::feature_matches;
using gcode::FeatureKind;

TEST_CASE("feature: each slicer's spelling names one kind", "[feature]") {
  CHECK(feature_kind("WALL-OUTER") == FeatureKind::OuterWall);           // Cura
  CHECK(feature_kind("External perimeter") == FeatureKind::OuterWall);   // PrusaSlicer
  CHECK(feature_kind("Outer wall") == FeatureKind::OuterWall);           // Orca
  CHECK(feature_kind("Perimeter") == FeatureKind::InnerWall);
  CHECK(feature_kind("FILL") == FeatureKind::Infill);
  CHECK(feature_kind("Sparse infill") == FeatureKind::Infill);
  CHECK(feature_kind("Internal solid infill") == FeatureKind::SolidInfill);
  CHECK(feature_kind("Top solid infill") == FeatureKind::TopSurface);
  CHECK(feature_kind("Skirt/Brim") == FeatureKind::Skirt);
  CHECK(feature_kind("Wipe tower") == FeatureKind::PrimeTower);
  CHECK(feature_kind("Support material interface") == FeatureKind::SupportInterface);
  CHECK(feature_kind("Custom") == FeatureKind::Custom);
  CHECK(feature_kind("wall-outer") == FeatureKind::OuterWall);
  CHECK(feature_kind("EXTERNAL PERIMETER") == FeatureKind::OuterWall);
  CHECK(feature_kind("Outer wall ") == FeatureKind::Unknown);  // no trimming: a different name
  CHECK(feature_kind("") == FeatureKind::Unknown);
  CHECK(feature_kind("PRIME-TOWERS") == FeatureKind::Unknown);
}

TEST_CASE("feature: a name asked for selects every spelling of its kind", "[feature]") {
  CHECK(feature_matches("WALL-OUTER", "External perimeter"));
  CHECK(feature_matches("outer wall", "WALL-OUTER"));
  CHECK(feature_matches("Support", "SUPPORT"));
  CHECK(feature_matches("Brim", "SKIRT"));  // one kind: the slicers mix them
  // Close names of other kinds stay apart.
  CHECK_FALSE(feature_matches("Perimeter", "External perimeter"));
  CHECK_FALSE(feature_matches("WALL-INNER", "WALL-OUTER"));
  CHECK_FALSE(feature_matches("SUPPORT", "SUPPORT-INTERFACE"));
  CHECK_FALSE(feature_matches("Solid infill", "Top solid infill"));
}

TEST_CASE("feature: unknown names match only themselves, case-insensitively", "[feature]") {
  CHECK(feature_matches("MY-FEATURE", "my-feature"));
  CHECK_FALSE(feature_matches("MY-FEATURE", "OTHER"));
  // Two names the table does not know are not one kind.
  CHECK_FALSE(feature_matches("Foo", "Bar"));
  CHECK_FALSE(feature_matches("", "WALL-OUTER"));
  CHECK(feature_matches("", ""));
}

TEST_CASE("feature: same_name compares ASCII letters case-insensitively", "[feature]") {
  CHECK(gcode::same_name("Gap Fill", "gap fill"));
  CHECK_FALSE(gcode::same_name("Gap fill", "Gap fil"));
  CHECK_FALSE(gcode::same_name("a-b", "a_b"));
  CHECK(gcode::same_name("", ""));
  CHECK_FALSE(gcode::same_name("\xc3\x89", "\xc3\xa9"));  // no case folding beyond ASCII
}
