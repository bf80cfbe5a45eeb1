#include "gcode/core/feature.hpp"

namespace gcode {

namespace {

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

struct Spelling {
  std::string_view name;
  FeatureKind kind;
};

// Cura (CuraEngine 4-5), PrusaSlicer/SuperSlicer/Slic3r, OrcaSlicer/BambuStudio.
constexpr Spelling kSpellings[] = {
    {"WALL-OUTER", FeatureKind::OuterWall},
    {"External perimeter", FeatureKind::OuterWall},
    {"Outer wall", FeatureKind::OuterWall},
    {"WALL-INNER", FeatureKind::InnerWall},
    {"Perimeter", FeatureKind::InnerWall},
    {"Inner wall", FeatureKind::InnerWall},
    {"Overhang perimeter", FeatureKind::OverhangWall},
    {"Overhang wall", FeatureKind::OverhangWall},
    {"FILL", FeatureKind::Infill},
    {"Internal infill", FeatureKind::Infill},
    {"Sparse infill", FeatureKind::Infill},
    {"SKIN", FeatureKind::SolidInfill},
    {"Solid infill", FeatureKind::SolidInfill},
    {"Internal solid infill", FeatureKind::SolidInfill},
    {"Top solid infill", FeatureKind::TopSurface},
    {"Top surface", FeatureKind::TopSurface},
    {"Bottom surface", FeatureKind::BottomSurface},
    {"Bridge infill", FeatureKind::Bridge},
    {"Internal bridge", FeatureKind::Bridge},
    {"Gap fill", FeatureKind::GapFill},
    {"Gap infill", FeatureKind::GapFill},
    {"SUPPORT", FeatureKind::Support},
    {"Support material", FeatureKind::Support},
    {"Support", FeatureKind::Support},
    {"SUPPORT-INTERFACE", FeatureKind::SupportInterface},
    {"Support material interface", FeatureKind::SupportInterface},
    {"Support interface", FeatureKind::SupportInterface},
    {"SKIRT", FeatureKind::Skirt},
    {"Skirt/Brim", FeatureKind::Skirt},
    {"Skirt", FeatureKind::Skirt},
    {"Brim", FeatureKind::Skirt},
    {"PRIME-TOWER", FeatureKind::PrimeTower},
    {"Wipe tower", FeatureKind::PrimeTower},
    {"Prime tower", FeatureKind::PrimeTower},
    {"Ironing", FeatureKind::Ironing},
    {"Custom", FeatureKind::Custom},
};

}  // namespace

bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}

FeatureKind feature_kind(std::string_view name) {
  for (const Spelling& s : kSpellings)
    if (same_name(s.name, name)) return s.kind;
  return FeatureKind::Unknown;
}

bool feature_matches(std::string_view wanted, std::string_view name) {
  if (same_name(wanted, name)) return true;
  FeatureKind kind = feature_kind(wanted);
  return kind != FeatureKind::Unknown && kind == feature_kind(name);
}

}  // namespace gcode
