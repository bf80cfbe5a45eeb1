#pragma once
// The objects of a file without labels (IceSL, Kiri:Moto, KISSlicer,
// Simplify3D, Slic3r, hand-written), from their footprints: the first
// layer's extrusions drawn on a grid of half millimetres and grouped into
// separate regions of the plate (a region that encloses another one, a
// skirt, is no object); each later extrusion belongs to the region it
// stands on (the regions grown by up to `reach` mm, each cell to the
// nearest). An extrusion that stands on no region, or on two, cannot be
// assigned: the listing says where, and the objects it touches cannot be
// cut.
//
// The blocks of an object are the stretches from just after the last
// extrusion of something else to the last extrusion of a run of that
// object's extrusions (its travel, lift and retraction included), so the
// excluder (object_excluder.hpp) can leave them out as it leaves out a
// labelled block.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gcode/objects/convex_hull.hpp"
#include "gcode/objects/object_table.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/report/estimator.hpp"

namespace gcode {

// Which object each input line belongs to, as line ranges in input order.
struct ObjectBlocks {
  struct Block {
    std::uint64_t first_line = 0;
    std::uint64_t last_line = 0;
    int object = -1;
  };
  std::vector<Block> blocks;
  // The object of input line `line`; `cursor` follows the lines in order.
  int object_at(std::uint64_t line, std::size_t& cursor) const;
};

// An extrusion no footprint takes.
struct FootprintProblem {
  std::uint64_t line = 0;
  int layer = 0;
  std::vector<int> objects;  // the footprints it touches (none: outside all)
};

// What the problems say, one line each ("line 1234 (layer 40): an extrusion
// on footprints 2 and 3"), at most `max` lines and a count of the rest.
std::vector<std::string> describe(const std::vector<FootprintProblem>& problems, std::size_t max = 5);

class FootprintStage : public Stage, private TimeSink {
 public:
  explicit FootprintStage(const EstimatorOptions& estimate = {}, double reach_mm = 3);
  ~FootprintStage() override;
  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override;
  // After the run.
  const ObjectTable& table() const { return table_; }
  const ObjectBlocks& blocks() const { return blocks_; }
  const std::vector<FootprintProblem>& problems() const { return problems_; }
  // Whether object `i` may be cut: no extrusion joins it to another
  // object or stands beside it outside every footprint on its layers.
  bool cuttable(int i) const;

 private:
  struct Grid;
  struct Pending {
    std::uint64_t line;
    int layer;
    double x0, y0, x1, y1, filament;
  };
  void on_time(std::int64_t tag, double seconds) override;
  void build();
  void assign(const Pending& e);
  void close_run(std::uint64_t next_first);
  Estimator estimator_;
  double reach_;
  std::vector<Pending> first_layer_;
  std::unique_ptr<Grid> grid_;
  bool built_ = false;
  int objects_ = 0;
  std::vector<HullBuilder> hulls_;
  std::vector<double> times_;        // [0] outside, [i + 1] object i
  std::vector<double> first_times_;  // per first-layer extrusion, until its object is known
  std::vector<int> first_object_;    // then its object (-1: none)
  // The run of extrusions being followed.
  int run_object_ = -2;
  std::uint64_t run_first_ = 1;
  std::uint64_t run_last_ = 0;
  std::uint64_t last_extrusion_ = 0;
  ObjectBlocks blocks_;
  std::vector<FootprintProblem> problems_;
  std::vector<bool> blocked_;
  ObjectTable table_;
};

}  // namespace gcode
