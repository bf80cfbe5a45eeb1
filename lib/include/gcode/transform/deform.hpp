#pragma once
// gc-deform's stage: every move of the layers through a DeformMap, exact to
// a tolerance, with its extrusion and speed following the deformation.
//
// Exact to a tolerance. Moving only the end points of a move leaves its
// straight segment to carry the deformation's error; here every move (G2/G3
// arcs too, which become G1 chords) is cut adaptively: a piece is cut in
// two where the image of a probe point (every 0.2 mm of it, at least three)
// lies farther than the tolerance (less the rounding of written
// coordinates) from the piece's chord, or where the images of its halves
// differ in length by more than that (a map that stretches unevenly, or
// jumps along the chord), so the written path stays within the tolerance of
// the image of the original one.
//
// Extrusion follows the deformation: the input move's bead is f / L mm of
// filament per mm (its cross-section); each piece gets that times the map's
// cross-section factor at its middle (deform_map.hpp) times its length as
// written. A move that pushes no filament forward (travel, a wipe) shares
// its E by length. F of extrusions is the input's times the speed factor,
// capped by max_speed and max_flow; travel keeps its F.
//
// Start and end code pass unchanged (the start code's purge line and the
// end code's park are not part of the shape); the first move into the
// layers starts where the start code left the head, and an extrusion that
// would begin away from the image of its start gets a travel there first.
// Lines outside the layers are rewritten only as far as the deformation
// makes them differ: an absolute E word is shifted by what the layers'
// filament changed (until a G92 E), a move without F gets the F the input
// had. Positions, E and F are followed as the file's own modes write them
// (G90/G91, M82/M83, G92), so relative and absolute files both come out
// right; a move whose image is itself (the identity, or where the map
// leaves the part alone) is passed byte for byte, arcs included.
//
// Refused (DeformError, with the input line; `force` lets the first two
// through): a point whose image would send the nozzle more than 0.1 mm +
// the tolerance below what earlier layers printed under it (0.5 mm cells),
// a jump (an image that stays farther than the tolerance from its chord
// down to pieces of 0.000001 mm, or an extrusion that starts away from where
// the last one ended), and always a point off the bed (below Z 0 by more
// than the tolerance, outside the bed, where the input was on it, or above
// its height, when they are known) or an
// image or factor that is not a finite number. Moves of the layers in
// inches (G20) are passed unchanged where the map leaves them alone (the
// identity) and refused elsewhere, unless `force` passes them unchanged.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gcode/core/geometry.hpp"
#include "gcode/core/line_builder.hpp"
#include "gcode/pipeline/stage.hpp"
#include "gcode/transform/deform_map.hpp"
#include "gcode/transform/printed_height.hpp"

namespace gcode {

class Diagnostics;

struct DeformOptions {
  double tolerance = 0.01;       // mm
  double max_speed = 0;          // mm/s, 0 = no cap
  double max_flow = 0;           // mm3/s, 0 = no cap
  double filament_diameter = 1.75;
  bool force = false;            // print through downward moves and jumps
  bool has_bed = false;
  Box2 bed;
  bool has_max_z = false;
  double max_z = 0;
  double section_low = 0.3;      // warn where the cross-section factor leaves [low, high]
  double section_high = 3;
  // Throws std::invalid_argument naming the option that makes no sense.
  void validate() const;
};

struct DeformStats {
  std::uint64_t moves = 0;        // moves deformed
  std::uint64_t unchanged = 0;    // moves of the layers whose image is themselves
  std::uint64_t pieces = 0;       // written for the deformed moves
  std::uint64_t arcs = 0;
  std::uint64_t capped = 0;       // pieces whose speed a cap lowered
  std::uint64_t outside = 0;      // extrusion pieces whose factor left [low, high]
  double section_min = 0, section_max = 0;  // cross-section factor over the extrusion pieces
  double speed_min = 0, speed_max = 0;      // mm/s of the extrusion pieces
  double filament = 0;            // mm written by the deformed extrusions
};

struct DeformError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Deformer : public Stage {
 public:
  // `precision`: the input's decimals per letter (Pipeline::precision).
  Deformer(DeformMap& map, const DeformOptions& options, const Precision& precision, Diagnostics* diagnostics);

  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  const DeformStats& stats() const { return stats_; }

 private:
  struct Piece {
    double t = 0;   // where it ends along the input move, 0..1
    Point3 image;   // where it ends after the map
  };
  Point3 on_move(double t) const;
  Point3 image_at(double t);
  void cut(double t0, const Point3& a, double t1, const Point3& b, int depth);
  bool plan(const TrackedLine& t, double path_before);
  bool leaves_alone(const TrackedLine& t, double path_before);
  bool in_step(const TrackedLine& t) const;
  bool in_step_outside(const TrackedLine& t) const;
  void write(const TrackedLine& t, Emitter& out);
  void write_piece(const TrackedLine& t, std::size_t k, double filament_per_mm, double image_length, Emitter& out);
  void travel_to(const Point3& p, const TrackedLine& t, Emitter& out);
  std::string xyz_words(const Point3& p, const MachineState& s);
  std::string_view comment_of(const TrackedLine& t) const;
  double section_at(const Point3& mid);
  double piece_feed(const TrackedLine& t, double e, double length, const Point3& mid);
  void append_e(double e, const MachineState& s, bool word);
  void append_feed(double feed);
  void check_along(const Point3& a, const Point3& b, bool extruding);
  void check_point(const Point3& p, bool extruding);
  bool on_bed(const Point3& p) const;
  void pass_outside(const TrackedLine& t, Emitter& out, bool in_layers = false);
  void follow(const TrackedLine& t);
  [[noreturn]] void refuse(std::uint64_t line, const std::string& why) const;

  DeformMap& map_;
  DeformOptions options_;
  const Precision& precision_;
  Diagnostics* diagnostics_;
  DeformStats stats_;
  PrintedHeight printed_;
  double filament_area_;
  double cut_tolerance_ = 0;
  bool entered_ = false;          // the layers have begun
  bool entered_written_ = false;  // a deformed move was written: the head is in the deformed space
  // The move being cut.
  Point3 from_, to_;
  bool arc_ = false;
  double arc_cx_ = 0, arc_cy_ = 0, arc_r_ = 0, arc_a0_ = 0, arc_sweep_ = 0;
  double s0_ = 0, length_ = 0;
  int layer_ = 0;
  std::uint64_t line_ = 0;
  Point3 start_image_;
  double moved_ = 0;              // largest |image - point| seen while cutting
  double shared_ = 0;             // E of a move without forward filament, shared out so far
  bool jumped_ = false;
  bool on_bed_ = true;            // the input move lies on the bed
  std::vector<Piece> pieces_;
  // The output stream, as written.
  std::array<Fixed, 3> out_xyz_{};
  Fixed out_e_;
  double e_target_ = 0;           // the exact E coordinate the output should be at
  double out_feed_ = 0;           // mm/min as written; 0 = none yet
  double path_ = 0;               // mm of input path so far (`s`)
  LineBuilder b_;
  std::string comment_;
};

}  // namespace gcode
