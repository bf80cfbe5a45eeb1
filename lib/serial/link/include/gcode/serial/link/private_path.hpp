#pragma once
// Files that steer or record a machine with a hot nozzle (the control FIFO,
// the journal) live only in folders nobody else can change: someone who may
// write to the folder could swap the file for one of their own. A sticky
// folder such as /tmp is fine (only owners may remove or rename its files).
#include <string>
#include <string_view>

namespace gcode::serial {

// The folder `path` is in ("." for a bare name, "/" for a file at the root).
std::string folder_of(const std::string& path);

// Why the folder may not hold such a file, or "" when it may (also when it
// does not exist yet: it is made 0700 then). `what` names the file in the
// message ("control FIFO", "journal").
std::string folder_problem(const std::string& dir, std::string_view what);

// Makes the folders of `path` that are missing (0700); throws on failure.
void make_private_folder(const std::string& path);

// The state folder of gc-send's files: $XDG_STATE_HOME/gc-send, else
// ~/.local/state/gc-send ("" when neither can be told).
std::string state_folder();

// "ttyACM0" from "/dev/ttyACM0", "virtual" from "virtual:time-scale=20".
std::string port_file_name(std::string_view port);

}  // namespace gcode::serial
