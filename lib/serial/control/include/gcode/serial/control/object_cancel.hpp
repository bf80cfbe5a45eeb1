#pragma once
// gc-send's `cancel object ID|NAME` and --exclude: objects of the plate left
// out host side, on every firmware (the firmware's own M486 or
// EXCLUDE_OBJECT is not relied on; its label lines are sent as they are).
//
// Each pipeline that feeds the printer (the input's, a swapped-in file's)
// runs a LiveExcluder first: the library's ObjectExcluder
// (objects/object_excluder.hpp), which drops the motion of the cancelled
// objects' blocks and writes, before the next kept line, what that line
// expects (the retraction, the E coordinate, the position, the feed rate).
// A cancel acts at once: the excluder leaves the object out from the next
// line it reads, also in the middle of its block; lines already handed to
// the sender (a line or two) and the printer's own buffer still run.
//
// Objects are learned as the lines stream (a pipe cannot be read ahead):
// from the file's declarations (EXCLUDE_OBJECT_DEFINE, M486 T) or each
// object's first label. A cancel names an object by its id (the slicer's
// number, else its place in order of appearance), its name, or its label's
// key. A name not seen yet is kept and applies when such an object
// appears (a later object, a swapped-in file's); at the end gc-send says
// which never did.
//
// The journal keeps the cancelled objects (journal_text), so gc-send
// --resume leaves them out again; a resume also reads the labels of the
// printed part (continue_from), so the numbering and the object the print
// stood in are the ones the first run had.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "gcode/core/diagnostics.hpp"
#include "gcode/objects/object_excluder.hpp"
#include "gcode/objects/object_tracker.hpp"
#include "gcode/pipeline/pipeline.hpp"

namespace gcode::serial {

class ObjectCancel;

// The objects a `cancel object` line or an --exclude value names: blanks
// or commas between them, "double quotes" around a name with blanks.
std::vector<std::string> object_terms(std::string_view text);

// The objects named by the printed part of an input (gc-send --resume
// reads it before going on), fed in pieces of any size.
class PrintedObjects {
 public:
  void feed(std::string_view bytes);
  // After the last piece (a last line without its newline is read too).
  const ObjectTracker& tracker();

 private:
  void read_line(std::string_view text);
  ObjectTracker tracker_;
  std::string partial_;
};

// One pipeline's excluder, told of each object as its pipeline names it.
class LiveExcluder final : public Stage {
 public:
  // `line_offset`: input lines before this pipeline's first (a resume, a
  // swap); `resumed_layer`: a resume's pipeline starts inside that layer,
  // and its lines up to the next layer are of it (not start code).
  LiveExcluder(ObjectCancel& owner, const Precision& precision, std::uint64_t line_offset, int resumed_layer = 0);
  void line(const TrackedLine& t, Emitter& out) override;
  void layer(const LayerInfo& info, const MachineState& before, Emitter& out) override;
  void finish(Emitter& out) override { excluder_.finish(out); }

  ObjectExcluder& excluder() { return excluder_; }
  const ObjectExcluder& excluder() const { return excluder_; }
  // The last input line it read (numbered as the print's).
  std::uint64_t last_line() const { return last_line_; }
  // Tells the owner of the objects named since it last did.
  void tell_owner();

 private:
  ObjectCancel& owner_;
  ObjectExcluder excluder_;
  std::uint64_t line_offset_;
  std::uint64_t last_line_ = 0;
  std::size_t known_ = 0;  // names the owner has been told of
};

class ObjectCancel {
 public:
  ObjectCancel(Diagnostics& diagnostics, const Precision& precision) : diag_(diagnostics), precision_(precision) {}

  // A new excluder, first in `pipeline` (before anything that changes lines).
  void add_stage(Pipeline& pipeline, std::uint64_t line_offset, int resumed_layer = 0);
  // gc-send --resume: the labels of the lines printed before (read before
  // the first excluder exists).
  void continue_from(const ObjectTracker& printed) {
    printed_ = printed;
    primed_ = true;
  }

  // `cancel object ...`: `text` the ids or names.
  void cancel(std::string_view text);
  // --exclude and the journal's list: cancelled from the start, quietly
  // when `quiet` (the journal's).
  void exclude(const std::vector<std::string>& terms, std::string_view source, bool quiet = false);
  // `objects`: one line each, with its state.
  std::vector<std::string> listing() const;
  // The status file's "objects" value: [{"id", "name", "state"}, ...].
  std::string json() const;
  // What the journal keeps: the cancelled objects, one a line (their keys
  // once seen, else as asked for).
  const std::string& journal_text() const { return journal_text_; }
  // After the print: what was left out; cancels that matched no object.
  std::vector<std::string> summary() const;
  bool any() const { return !cancelled_.empty(); }

  // From a LiveExcluder: its pipeline named objects beyond `known`.
  void named(LiveExcluder& stage, std::size_t known);

 private:
  struct Cancelled {
    std::string term;           // as asked for, or the key once matched
    std::string source;         // "cancel object", "--exclude", "the journal"
    bool matched = false;
    std::string shown;          // "ID NAME" once matched
    std::uint64_t after_line = 0;  // the input line after which it took effect (0: from the start)
  };
  static bool matches(const std::string& term, const ObjectName& n);
  bool is_cancelled(const ObjectName& n) const;
  const Cancelled* cancel_of(const ObjectName& n) const;
  void apply(LiveExcluder& stage, int index, Cancelled& c);
  void update_journal_text();
  LiveExcluder* current() const { return stages_.empty() ? nullptr : stages_.back().get(); }
  std::string state_of(int index, const ObjectName& n) const;

  Diagnostics& diag_;
  const Precision& precision_;
  std::vector<std::unique_ptr<LiveExcluder>> stages_;  // the newest is fed now
  std::vector<Cancelled> cancelled_;
  ObjectTracker printed_;
  bool primed_ = false;
  std::string journal_text_;
};

}  // namespace gcode::serial
