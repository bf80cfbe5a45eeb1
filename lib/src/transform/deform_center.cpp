#include "gcode/transform/deform_center.hpp"

#include "gcode/pipeline/pipeline.hpp"

namespace gcode {

namespace {

class ExtrusionBox : public Stage {
 public:
  void line(const TrackedLine& t, Emitter& out) override {
    if (t.region == Region::Layer && t.move.extruding) {
      box.add(t.move.start[kX], t.move.start[kY]);
      box.add(t.move.end[kX], t.move.end[kY]);
    }
    out.pass(t);
  }
  Box2 box;
};

}  // namespace

bool extrusion_centre(int fd, const LayerMarkers& markers, int e_relative, Point2& centre) {
  Pipeline reading(markers);
  if (e_relative == 0 || e_relative == 1) reading.set_e_mode(e_relative == 1);
  ExtrusionBox box;
  reading.add(box);
  reading.run(fd);
  if (box.box.empty()) return false;
  centre = box.box.centre();
  return true;
}

}  // namespace gcode
