#pragma once
// The journal's first record (journal.hpp): which input and port a print
// was, so that a resume given another file, or the same path changed since,
// is refused before anything is sent.
#include <string>
#include <string_view>

#include "gcode/serial/journal/input_identity.hpp"
#include "gcode/serial/journal/journal_record.hpp"

namespace gcode::serial {

JournalFields journal_header(const InputIdentity& input, std::string_view port);

// Why `now` is not the input the journal was written for, or "" when it may
// be: a regular file must have the same path, size and modification time; a
// stream (a pipeline re-run) can only be told by the hash of its bytes,
// which the resume checks as it reads them again.
std::string input_mismatch(const JournalFields& header, const InputIdentity& now);

}  // namespace gcode::serial
