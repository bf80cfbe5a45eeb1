#pragma once
// gc-send's control verbs, one table (control_verb_table.cpp): the words a line
// written into the control FIFO may begin with, the argument each takes, the
// line --help shows for it, what PrintControl does with it, and what of it the
// journal keeps so that --resume puts it back. The FIFO's parser
// (control_fifo.hpp), PrintControl::command, --help, the journal
// (SendSession) and a resume (send_job) all read this table; the man page's
// CONTROL entries are checked against it by a consistency test. A new verb is
// a row here (and its entry in man/gc-send.1).
#include <span>
#include <string>
#include <string_view>

namespace gcode::serial {

class PrintControl;
struct ControlVerb;

// One line of the FIFO, read by the table.
struct ControlCommand {
  const ControlVerb* verb = nullptr;  // nullptr: a line it cannot read (reported, never fatal)
  std::string argument;  // the rest of the line, trimmed ("" when none); for no verb, why
  double number = 0;     // speed F

  bool is(std::string_view name) const;
};

struct ControlVerb {
  std::string_view name = {};      // its words, lower case: "pause now"
  std::string_view argument = {};  // what follows, as --help and the man page name it ("F", "FILE"); "": none
  std::string_view help = {};      // its line in --help
  // Checks the argument and reads it into the command (ControlCommand::number);
  // returns why it cannot ("" when it can). Null: any text will do.
  std::string (*read)(std::string_view argument, ControlCommand& command) = nullptr;
  void (*handle)(PrintControl& control, const ControlCommand& command) = nullptr;
  // Kept by the journal: the field it is kept in ("": not kept), the value
  // the control holds now, and how a --resume puts a kept value back (a
  // missing field comes as "", and must leave the control as it starts).
  std::string_view journal_field = {};
  std::string (*journal)(const PrintControl& control) = nullptr;
  void (*restore)(PrintControl& control, std::string_view kept) = nullptr;

  // "speed F": as --help and the man page write it.
  std::string usage() const;
};

// Every verb, in the order --help and the man page list them. Defined in
// control_verb_table.cpp, beside PrintControl's actions its rows call.
std::span<const ControlVerb> control_verbs();
// Parses one line ("pause", "pause now", "speed 1.5", "gcode G1 Z10", ...)
// by the table: case-insensitive words, blanks around and between them
// ignored, the verb with the most words that begin the line taken. A line
// it cannot read (an unknown verb, a missing, extra or bad argument) has no
// verb and the reason in `argument`.
ControlCommand parse_control_command(std::string_view line);
// By its exact name ("pause now"); nullptr for none.
const ControlVerb* find_control_verb(std::string_view name);
// The list --help shows: one verb a line, its usage and its help.
std::string control_verbs_help();

}  // namespace gcode::serial
