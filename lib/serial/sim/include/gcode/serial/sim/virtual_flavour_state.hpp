#pragma once
// What a firmware's own ways leave the virtual printer in, beyond Marlin's
// (virtual_printer_flavour.cpp acts on it): Klipper shut down, refusing
// every command but a few until FIRMWARE_RESTART, and that restart due once
// the command's ok is out; Prusa's own pause (M601) on until the user
// resumes.
#include <string>
#include <string_view>

namespace gcode::serial {

class FlavourState {
 public:
  bool shut_down() const { return shut_down_; }
  // Why, as Klipper says it in every refusal.
  const std::string& shutdown_reason() const { return shutdown_reason_; }
  void shut_down_for(std::string_view why) {
    shut_down_ = true;
    shutdown_reason_ = std::string(why);
  }

  // FIRMWARE_RESTART or RESTART: the restart follows its ok.
  void restart_after_ok() { restart_pending_ = true; }
  // Whether that restart is due now (once).
  bool take_restart() {
    const bool due = restart_pending_;
    restart_pending_ = false;
    return due;
  }

  bool own_paused() const { return own_paused_; }
  void own_pause() { own_paused_ = true; }
  // The user answered: whether that ends an own pause (it says it resumed).
  bool take_resume() {
    const bool was = own_paused_;
    own_paused_ = false;
    return was;
  }

  // The board restarted: no shutdown, no pause (a restart already due stays due).
  void restarted() { shut_down_ = own_paused_ = false; }

 private:
  bool shut_down_ = false;
  std::string shutdown_reason_;
  bool restart_pending_ = false;
  bool own_paused_ = false;
};

}  // namespace gcode::serial
