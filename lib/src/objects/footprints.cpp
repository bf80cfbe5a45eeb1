#include "gcode/objects/footprints.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace gcode {

namespace {

constexpr double kCell = 0.5;            // mm
constexpr std::int64_t kFirstLayerTag = 1LL << 40;  // estimator tags of first-layer lines: + extrusion index
constexpr int kNone = -1;
constexpr int kBetween = -2;             // as near to two footprints

}  // namespace

int ObjectBlocks::object_at(std::uint64_t line, std::size_t& cursor) const {
  while (cursor < blocks.size() && blocks[cursor].last_line < line) ++cursor;
  if (cursor < blocks.size() && blocks[cursor].first_line <= line) return blocks[cursor].object;
  return -1;
}

// The plate in cells: which footprint each cell belongs to.
struct FootprintStage::Grid {
  double x0 = 0, y0 = 0;
  int w = 0, h = 0;
  std::vector<int> cell;
  int* at(double x, double y) {
    const int i = static_cast<int>(std::floor((x - x0) / kCell)), j = static_cast<int>(std::floor((y - y0) / kCell));
    if (i < 0 || j < 0 || i >= w || j >= h) return nullptr;
    return &cell[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)];
  }
  int label(double x, double y) {
    const int* c = at(x, y);
    return c == nullptr ? kNone : *c;
  }
};

FootprintStage::FootprintStage(const EstimatorOptions& estimate, double reach_mm) : estimator_(estimate, this), reach_(reach_mm) {}

FootprintStage::~FootprintStage() = default;

void FootprintStage::on_time(std::int64_t tag, double seconds) {
  if (tag >= kFirstLayerTag) {
    const auto i = static_cast<std::size_t>(tag - kFirstLayerTag);
    if (built_ && i < first_object_.size()) {
      times_[static_cast<std::size_t>(first_object_[i] + 1)] += seconds;
      return;
    }
    if (first_times_.size() <= i) first_times_.resize(i + 1);
    first_times_[i] += seconds;
    return;
  }
  const auto i = static_cast<std::size_t>(tag);
  if (times_.size() <= i) times_.resize(i + 1);
  times_[i] += seconds;
}

void FootprintStage::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  if (info.index >= 2 && !built_) build();
  out.layer(info, before);
}

void FootprintStage::line(const TrackedLine& t, Emitter& out) {
  estimator_.add(t.line, t.move);
  if (t.move.extruding && t.region == Region::Layer) {
    Pending e{t.raw.number, t.layer, t.move.start[kX], t.move.start[kY], t.move.end[kX], t.move.end[kY], t.move.filament};
    if (!built_) {
      first_layer_.push_back(e);
      estimator_.set_tag(kFirstLayerTag + static_cast<std::int64_t>(first_layer_.size() - 1));
    } else {
      assign(e);
    }
  }
  out.pass(t);
}

void FootprintStage::build() {
  built_ = true;
  grid_ = std::make_unique<Grid>();
  Grid& g = *grid_;
  Box2 box;
  for (const Pending& e : first_layer_) {
    box.add(e.x0, e.y0);
    box.add(e.x1, e.y1);
  }
  if (box.empty()) return;
  const double pad = reach_ + 2 * kCell;
  g.x0 = box.min_x - pad;
  g.y0 = box.min_y - pad;
  g.w = static_cast<int>(std::ceil((box.width() + 2 * pad) / kCell)) + 1;
  g.h = static_cast<int>(std::ceil((box.depth() + 2 * pad) / kCell)) + 1;
  g.cell.assign(static_cast<std::size_t>(g.w) * static_cast<std::size_t>(g.h), kNone);
  // Draw the first layer: every extrusion, sampled at a quarter cell.
  constexpr int kDrawn = -3;
  for (const Pending& e : first_layer_) {
    const double len = std::hypot(e.x1 - e.x0, e.y1 - e.y0);
    const int steps = std::max(1, static_cast<int>(std::ceil(len / (kCell / 4))));
    for (int s = 0; s <= steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      if (int* c = g.at(e.x0 + f * (e.x1 - e.x0), e.y0 + f * (e.y1 - e.y0))) *c = kDrawn;
    }
  }
  // Regions: cells joined by a side or a corner.
  std::vector<Box2> regions;
  std::vector<std::size_t> queue;
  for (std::size_t start = 0; start < g.cell.size(); ++start) {
    if (g.cell[start] != kDrawn) continue;
    const int id = static_cast<int>(regions.size());
    regions.emplace_back();
    queue.assign(1, start);
    g.cell[start] = id;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int i = static_cast<int>(queue[q] % static_cast<std::size_t>(g.w)), j = static_cast<int>(queue[q] / static_cast<std::size_t>(g.w));
      regions[static_cast<std::size_t>(id)].add(g.x0 + i * kCell, g.y0 + j * kCell);
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj;
          if (ni < 0 || nj < 0 || ni >= g.w || nj >= g.h) continue;
          const std::size_t n = static_cast<std::size_t>(nj) * static_cast<std::size_t>(g.w) + static_cast<std::size_t>(ni);
          if (g.cell[n] != kDrawn) continue;
          g.cell[n] = id;
          queue.push_back(n);
        }
    }
  }
  // A region around another one (a skirt) is no object; the others are
  // numbered in the order of their first extrusion.
  std::vector<int> object_of(regions.size(), kNone);
  auto encloses = [](const Box2& a, const Box2& b) {
    return a.min_x < b.min_x && a.min_y < b.min_y && a.max_x > b.max_x && a.max_y > b.max_y;
  };
  for (const Pending& e : first_layer_) {
    const int r = g.label(e.x0, e.y0);
    if (r < 0 || object_of[static_cast<std::size_t>(r)] != kNone) continue;
    bool skirt = false;
    for (std::size_t o = 0; o < regions.size(); ++o)
      if (static_cast<int>(o) != r && encloses(regions[static_cast<std::size_t>(r)], regions[o])) skirt = true;
    object_of[static_cast<std::size_t>(r)] = skirt ? kBetween : objects_++;
  }
  for (int& c : g.cell)
    if (c >= 0) c = object_of[static_cast<std::size_t>(c)] == kBetween ? kNone : object_of[static_cast<std::size_t>(c)];
  // Grow each footprint by `reach`: each cell to the nearest, a tie to none.
  std::vector<int> dist(g.cell.size(), -1);
  std::deque<std::size_t> grow;
  for (std::size_t c = 0; c < g.cell.size(); ++c)
    if (g.cell[c] >= 0) dist[c] = 0, grow.push_back(c);
  const int max_steps = static_cast<int>(std::ceil(reach_ / kCell));
  while (!grow.empty()) {
    const std::size_t c = grow.front();
    grow.pop_front();
    if (dist[c] >= max_steps || g.cell[c] < 0) continue;
    const int i = static_cast<int>(c % static_cast<std::size_t>(g.w)), j = static_cast<int>(c / static_cast<std::size_t>(g.w));
    const int d4[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& d : d4) {
      const int ni = i + d[0], nj = j + d[1];
      if (ni < 0 || nj < 0 || ni >= g.w || nj >= g.h) continue;
      const std::size_t n = static_cast<std::size_t>(nj) * static_cast<std::size_t>(g.w) + static_cast<std::size_t>(ni);
      if (dist[n] < 0) {
        dist[n] = dist[c] + 1;
        g.cell[n] = g.cell[c];
        grow.push_back(n);
      } else if (dist[n] == dist[c] + 1 && g.cell[n] != g.cell[c]) {
        g.cell[n] = kBetween;
      }
    }
  }
  table_.objects.resize(static_cast<std::size_t>(objects_));
  hulls_.resize(static_cast<std::size_t>(objects_));
  blocked_.assign(static_cast<std::size_t>(objects_), false);
  times_.resize(static_cast<std::size_t>(objects_) + 1);
  first_times_.resize(first_layer_.size());
  first_object_.resize(first_layer_.size());
  for (std::size_t k = 0; k < first_layer_.size(); ++k) {
    assign(first_layer_[k]);
    first_object_[k] = run_object_;
    times_[static_cast<std::size_t>(run_object_ + 1)] += first_times_[k];
  }
  first_layer_.clear();
}

void FootprintStage::close_run(std::uint64_t next_first) {
  if (run_object_ >= -1 && run_last_ >= run_first_) blocks_.blocks.push_back({run_first_, run_last_, run_object_});
  run_first_ = next_first;
}

void FootprintStage::assign(const Pending& e) {
  Grid& g = *grid_;
  const int a = g.cell.empty() ? kNone : g.label(e.x0, e.y0);
  const int b = g.cell.empty() ? kNone : g.label(e.x1, e.y1);
  const int m = g.cell.empty() ? kNone : g.label((e.x0 + e.x1) / 2, (e.y0 + e.y1) / 2);
  int object = kNone;
  if (a >= 0 && a == b && b == m) {
    object = a;
  } else if (e.layer > 1) {
    // On a later layer, beside or between the footprints: say so.
    FootprintProblem p{e.line, e.layer, {}};
    for (int o : {a, b, m})
      if (o >= 0 && std::find(p.objects.begin(), p.objects.end(), o) == p.objects.end()) p.objects.push_back(o);
    for (int o : p.objects) blocked_[static_cast<std::size_t>(o)] = true;
    if (problems_.size() < 1000) problems_.push_back(std::move(p));
  }
  if (object != run_object_) {
    close_run(last_extrusion_ + 1);
    run_object_ = object;
  }
  run_last_ = e.line;
  last_extrusion_ = e.line;
  estimator_.set_tag(object + 1);
  if (object < 0) {
    table_.outside.filament_mm += e.filament;
    return;
  }
  PlateObject& o = table_.objects[static_cast<std::size_t>(object)];
  if (o.first_layer == 0) o.first_layer = e.layer;
  o.last_layer = e.layer;
  o.filament_mm += e.filament;
  o.box.add(e.x0, e.y0);
  o.box.add(e.x1, e.y1);
  hulls_[static_cast<std::size_t>(object)].add(e.x0, e.y0);
  hulls_[static_cast<std::size_t>(object)].add(e.x1, e.y1);
}

bool FootprintStage::cuttable(int i) const {
  return i >= 0 && static_cast<std::size_t>(i) < blocked_.size() && !blocked_[static_cast<std::size_t>(i)];
}

void FootprintStage::finish(Emitter& out) {
  if (!built_) build();
  estimator_.finish();
  close_run(last_extrusion_ + 1);
  times_.resize(static_cast<std::size_t>(objects_) + 1);
  for (std::size_t i = 0; i < table_.objects.size(); ++i) {
    PlateObject& o = table_.objects[i];
    o.id = std::to_string(i);
    o.name = "footprint " + std::to_string(i);
    o.outline = hulls_[i].hull();
    o.time_s = times_[i + 1];
    o.source = ObjectSource::Footprint;
  }
  table_.outside.time_s = times_[0];
  (void)out;
}

std::vector<std::string> describe(const std::vector<FootprintProblem>& problems, std::size_t max) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < problems.size() && i < max; ++i) {
    const FootprintProblem& p = problems[i];
    std::string s = "line " + std::to_string(p.line) + " (layer " + std::to_string(p.layer) + "): an extrusion ";
    if (p.objects.empty()) {
      s += "outside every footprint";
    } else {
      s += p.objects.size() == 1 ? "beside footprint " : "on footprints ";
      for (std::size_t k = 0; k < p.objects.size(); ++k) s += (k == 0 ? "" : " and ") + std::to_string(p.objects[k]);
    }
    out.push_back(std::move(s));
  }
  if (problems.size() > max) out.push_back("and " + std::to_string(problems.size() - max) + " more");
  return out;
}

}  // namespace gcode
