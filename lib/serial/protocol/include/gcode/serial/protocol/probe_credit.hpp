#pragma once
// How many moves a pace probe's answer lets go (pacer.hpp), like TCP's slow
// start. A probe (a bare G1, which Marlin holds until a block is free) that
// is answered at once says the planner had room after every move ahead of
// it; one answered late says a block just ended, so the planner was full.
// A probe found room: one move goes on its word, as always; each further
// probe in a row that finds room, sent right behind the moves the one
// before let go, doubles them (1, 2, 4 ... up to the planner's blocks). A
// printer the link cannot keep full (it drains its blocks faster than the
// line refills them, or it answers at once) is so fed at the link's speed;
// its probes keep finding room. A probe answered late puts it back to one:
// at the file's pace the planner is full, its probes come late and one
// move goes per block that ends (the moves ahead of the nozzle stay within
// the planner's size). A move that waited for a block stops the moves
// let go that have not gone, and the next probe does not double them (a
// move's lateness is partly the host's; the probe behind it says whether
// the planner was full).
namespace gcode::serial {

class ProbeCredit {
 public:
  // A probe answered; `room`: at once; `wanted`: one move per probe may be
  // too few (the printer may run the moves of a round trip in less time).
  // Returns the moves it lets go on top of the one block the pacer's model
  // frees for it.
  int answered(bool room, bool wanted, int planner_blocks);
  // A move waited for a block: the planner was full (or the host slow).
  void full();
  // May a move go beyond the model (and takes it)?
  bool take();
  // The next probe may go: every move let go has gone, or a quarter of
  // them is left (the probe's answer then comes before they have, and the
  // line is kept busy: a printer fed at the link's speed).
  bool due() const { return left_ <= lead_; }
  // Moves let go and not gone yet.
  int left() const { return left_; }
  // Moves the next probe that finds room lets go.
  int size() const { return size_; }

 private:
  int size_ = 1;       // moves the next probe that finds room lets go
  int left_ = 0;       // of the last one's, not yet gone
  int lead_ = 0;       // of them left when the next probe may go
  bool full_ = false;  // a move waited since the last probe's answer
};

}  // namespace gcode::serial
