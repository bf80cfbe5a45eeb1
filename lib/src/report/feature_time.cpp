#include "gcode/report/feature_time.hpp"

#include <cmath>

#include "gcode/core/feature.hpp"

namespace gcode {

namespace {
// Tags: a feature id (0, 1, ...) for extrusion, else one of these.
constexpr std::int64_t kUnnamed = -1;
constexpr std::int64_t kTravel = -2;
constexpr std::int64_t kLayerChange = -3;
constexpr std::int64_t kRetract = -4;
constexpr std::int64_t kStart = -5;
constexpr std::int64_t kEnd = -6;

bool is_wall(std::string_view name) {
  const FeatureKind k = feature_kind(name);
  return k == FeatureKind::OuterWall || k == FeatureKind::InnerWall || k == FeatureKind::OverhangWall;
}

std::int64_t tag_of(const TrackedLine& t) {
  if (t.region == Region::StartCode) return kStart;
  if (t.region == Region::EndCode) return kEnd;
  const Move& m = t.move;
  if (m.length <= 1e-9) return kRetract;  // E only (or no motion at all)
  if (m.filament > 0) return t.feature >= 0 ? t.feature : kUnnamed;
  return std::abs(m.end[kZ] - m.start[kZ]) > 1e-9 ? kLayerChange : kTravel;
}
}  // namespace

double FeatureTimes::layers() const {
  double t = unnamed + travel + layer_change + retract + acceleration + waits;
  for (const Feature& f : features) t += f.seconds;
  return t;
}

double FeatureTimes::walls() const {
  double t = 0;
  for (const Feature& f : features)
    if (is_wall(f.name)) t += f.seconds;
  return t;
}

double FeatureTimes::other_extrusion() const {
  double t = unnamed;
  for (const Feature& f : features)
    if (!is_wall(f.name)) t += f.seconds;
  return t;
}

FeatureTimer::FeatureTimer(const EstimatorOptions& options) : estimator_(options, this) {}

void FeatureTimer::line(const TrackedLine& t, Emitter& out) {
  out.pass(t);
  estimator_.set_tag(tag_of(t));
  estimator_.add(t.line, t.move);
}

void FeatureTimer::finish(Emitter&) { estimator_.finish(); }

void FeatureTimer::on_time(std::int64_t tag, double seconds) {
  if (tag == kStart)
    totals_.start += seconds;
  else if (tag == kEnd)
    totals_.end += seconds;
  else
    totals_.waits += seconds;
}

void FeatureTimer::on_motion(std::int64_t tag, double seconds, double cruise_seconds) {
  if (tag == kStart || tag == kEnd) return on_time(tag, seconds);
  totals_.acceleration += seconds - cruise_seconds;
  switch (tag) {
    case kUnnamed: totals_.unnamed += cruise_seconds; return;
    case kTravel: totals_.travel += cruise_seconds; return;
    case kLayerChange: totals_.layer_change += cruise_seconds; return;
    case kRetract: totals_.retract += cruise_seconds; return;
    default: break;
  }
  const auto id = static_cast<std::size_t>(tag);
  if (by_feature_.size() <= id) by_feature_.resize(id + 1, 0.0);
  by_feature_[id] += cruise_seconds;
}

}  // namespace gcode
