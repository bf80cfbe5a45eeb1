// Firmware descriptions (core/firmware.hpp): each quirk a named flag, looked
// up by the slicer's flavour name.
#include <catch2/catch.hpp>

#include "gcode/core/firmware.hpp"
#include "gcode/core/line.hpp"

using namespace gcode;

namespace {

bool unbounded(const FirmwareFlavor& f, const char* text) { return f.is_unbounded(Line::parse(text)); }
bool instant(const FirmwareFlavor& f, const char* text) { return f.is_instant(Line::parse(text)); }

}  // namespace

TEST_CASE("firmware: Marlin 2's quirks", "[firmware]") {
  const FirmwareFlavor& m = marlin2_firmware();
  CHECK(m.name == "marlin2");
  CHECK(m.g90_g91_set_e_mode);
  CHECK(m.m220_backup_restore);
  CHECK(m.m220_whole_percent);
  CHECK(m.checks_line_numbers);
  for (const char* c : {"M109 S200", "M190 S60", "G28", "G29", "G4 P500", "M0", "M600", "G12"}) {
    INFO(c);
    CHECK(unbounded(m, c));
    CHECK(m.is_long_running(Line::parse(c)));
  }
  CHECK_FALSE(unbounded(m, "M400"));
  CHECK(m.waits_for_planner(Line::parse("M400")));
  CHECK(m.is_long_running(Line::parse("M400")));
  for (const char* c : {"G90", "G92 E0", "M104 S200", "M106 S255", "M117 hello", "M220 S150", "M221 S95"}) {
    INFO(c);
    CHECK(instant(m, c));
    CHECK_FALSE(m.is_long_running(Line::parse(c)));
  }
  for (const char* c : {"G1 X10", "M84", "M109 S200", "M400", "; M104", "T1"}) {
    INFO(c);
    CHECK_FALSE(instant(m, c));
  }
}

TEST_CASE("firmware: flavours by the slicer's name", "[firmware]") {
  CHECK(find_firmware("marlin2") == &marlin2_firmware());
  CHECK(find_firmware("Marlin2") == &marlin2_firmware());
  REQUIRE(find_firmware("marlin") == &marlin1_firmware());
  CHECK_FALSE(find_firmware("marlin")->m220_backup_restore);  // Marlin 1 has no M220 B/R
  CHECK(find_firmware("marlin")->g90_g91_set_e_mode);
  CHECK(find_firmware("klipper") == &klipper_firmware());
  CHECK(find_firmware("reprapfirmware") == &rrf_firmware());
  CHECK(find_firmware("RRF") == &rrf_firmware());
  CHECK(find_firmware("prusa") == &prusa_firmware());
  CHECK(find_firmware("smoothie") == nullptr);  // not described yet
  CHECK(find_firmware("") == nullptr);
}

TEST_CASE("firmware: Klipper's, Prusa's and RepRapFirmware's quirks", "[firmware]") {
  const FirmwareFlavor& k = klipper_firmware();
  CHECK_FALSE(k.checks_line_numbers);
  CHECK_FALSE(k.g90_g91_set_e_mode);
  CHECK_FALSE(k.m220_backup_restore);
  CHECK_FALSE(k.m220_whole_percent);
  CHECK_FALSE(k.busy_keepalive);
  CHECK_FALSE(k.advanced_ok_possible);
  CHECK(unbounded(k, "G28"));
  CHECK(instant(k, "M204 S1000"));
  CHECK_FALSE(k.waits_silently(Line::parse("M600")));
  const FirmwareFlavor& p = prusa_firmware();
  CHECK(p.reports_own_pause);
  CHECK(p.busy_keepalive);
  CHECK(p.m220_backup_restore);
  CHECK(p.waits_silently(Line::parse("M600")));
  CHECK(p.waits_silently(Line::parse("M115 U3.13.0")));
  CHECK_FALSE(p.waits_silently(Line::parse("M115")));  // the report itself answers at once
  CHECK(unbounded(p, "G80"));
  CHECK(unbounded(p, "M115 U3.13.0"));
  const FirmwareFlavor& r = rrf_firmware();
  CHECK(r.checks_line_numbers);
  CHECK_FALSE(r.busy_keepalive);
  CHECK_FALSE(r.g90_g91_set_e_mode);
  CHECK(unbounded(r, "G32"));
  for (const FirmwareFlavor* f : {&marlin2_firmware(), &marlin1_firmware(), &k, &r}) {
    INFO(f->name);
    CHECK_FALSE(f->reports_own_pause);
    CHECK_FALSE(f->waits_silently(Line::parse("M600")));
  }
}

TEST_CASE("firmware: the flavour from the FIRMWARE_NAME of an M115 answer", "[firmware]") {
  CHECK(find_firmware_by_report("Klipper") == &klipper_firmware());
  CHECK(find_firmware_by_report("Prusa-Firmware 3.13.3 based on Marlin") == &prusa_firmware());
  CHECK(find_firmware_by_report(" RepRapFirmware for Duet 3 MB6HC") == &rrf_firmware());
  CHECK(find_firmware_by_report("Marlin 2.1.2 (Github)") == &marlin2_firmware());
  CHECK(find_firmware_by_report("Marlin 1.1.9") == &marlin1_firmware());
  CHECK(find_firmware_by_report("Marlin bugfix-2.1.x") == nullptr);  // the configured one stays
  CHECK(find_firmware_by_report("Smoothieware") == nullptr);
  CHECK(find_firmware_by_report("") == nullptr);
}
