#include "gcode/serial/link/private_path.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

namespace gcode::serial {

std::string folder_of(const std::string& path) {
  std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string folder_problem(const std::string& dir, std::string_view what) {
  struct stat ds{};
  if (::stat(dir.c_str(), &ds) != 0) return std::string();
  if ((ds.st_mode & S_ISVTX) != 0) return std::string();
  bool foreign = ds.st_uid != ::getuid() && ds.st_uid != 0;
  if (!foreign && (ds.st_mode & (S_IWGRP | S_IWOTH)) == 0) return std::string();
  return fmt::format("{} refused: its folder {} can be changed by others (owner uid {}, mode {:o})", what, dir,
                     ds.st_uid, ds.st_mode & 07777);
}

void make_private_folder(const std::string& path) {
  std::string dir = folder_of(path);
  if (dir == "." || dir == "/") return;
  // Every missing folder on the way (~/.local/state may not be there yet).
  for (std::size_t at = 1; at <= dir.size(); ++at) {
    if (at < dir.size() && dir[at] != '/') continue;
    std::string part = dir.substr(0, at);
    if (::mkdir(part.c_str(), 0700) != 0 && errno != EEXIST)
      throw std::runtime_error(fmt::format("cannot create {}: {}", part, std::strerror(errno)));
  }
}

std::string state_folder() {
  const char* state = std::getenv("XDG_STATE_HOME");
  if (state != nullptr && state[0] == '/') return std::string(state) + "/gc-send";
  const char* home = std::getenv("HOME");
  if (home != nullptr && home[0] == '/') return std::string(home) + "/.local/state/gc-send";
  return std::string();
}

std::string port_file_name(std::string_view port) {
  std::size_t slash = port.rfind('/');
  std::string name(slash == std::string_view::npos ? port : port.substr(slash + 1));
  std::size_t colon = name.find(':');
  if (colon != std::string::npos) name.resize(colon);  // "virtual:time-scale=20"
  if (name.empty()) name = "port";
  return name;
}

}  // namespace gcode::serial
