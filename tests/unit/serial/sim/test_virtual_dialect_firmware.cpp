// The simulated printer's dialects (gcode/serial/virtual_dialect.hpp) and
// the sender's firmware descriptions (gcode/core/firmware.hpp) are kept
// apart, what a printer does and what a host assumes of it; the names are
// one list (firmwares()). Here: each firmware of that list has a dialect,
// virtual:firmware= takes each of its names, and the two agree on every
// fact both hold.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "gcode/core/firmware.hpp"
#include "gcode/serial/sim/virtual_dialect.hpp"
#include "gcode/serial/sim/virtual_printer_options.hpp"

using namespace gcode;
using namespace gcode::serial;

namespace test_serial_virtual_dialect_firmware {

// The FIRMWARE_NAME of a dialect's answer to M115, as a host reads it.
std::string reported_name(const ReplyDialect& d) {
  VirtualPrinterConfig config;
  config.report_link = false;
  std::string first = d.firmware_report(config).front();
  std::size_t at = first.find("FIRMWARE_NAME:");
  return at == std::string::npos ? std::string() : first.substr(at + 14);
}

}  // namespace test_serial_virtual_dialect_firmware

TEST_CASE("virtual dialects: one for each firmware of the list, by each of its names", "[serial][dialect]") {
  REQUIRE(dialects().size() == firmwares().size());
  for (const FirmwareFlavor* f : firmwares()) {
    INFO(f->name);
    const ReplyDialect* d = find_dialect(f->name);
    REQUIRE(d != nullptr);
    CHECK(&d->firmware() == f);
    if (!f->also_named.empty()) CHECK(find_dialect(f->also_named) == d);
    VirtualPrinterConfig c;
    CHECK_NOTHROW(parse_virtual_options("firmware=" + std::string(f->name), c));
    CHECK(c.firmware == f->name);
  }
  VirtualPrinterConfig c;
  try {
    parse_virtual_options("firmware=smoothie", c);
    FAIL("smoothie taken");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()) == "virtual printer option firmware: 'smoothie' is not " + firmware_names());
  }
}

TEST_CASE("virtual dialects: each agrees with the sender's description of its firmware", "[serial][dialect]") {
  using test_serial_virtual_dialect_firmware::reported_name;
  for (const ReplyDialect* d : dialects()) {
    const FirmwareFlavor& f = d->firmware();
    const DialectBehaviour& b = d->behaviour();
    INFO(f.name);
    CHECK(b.checks_line_numbers == f.checks_line_numbers);
    CHECK(b.busy_keepalive == f.busy_keepalive);
    CHECK(b.empty_move_waits == f.empty_move_waits);
    CHECK(b.own_pause == f.reports_own_pause);
    CHECK(b.user_waits == !f.silent_user_waits.empty());
    // Answered as soon as queued: it reads every byte and keeps seconds of
    // motion, not planner blocks.
    CHECK(b.reads_everything == f.ok_when_queued);
    CHECK((b.buffer_seconds > 0) == f.ok_when_queued);
    // ADVANCED_OK when the printer is built with it.
    CHECK((d->ok(7, true, 3, 2) != "ok") == f.advanced_ok_possible);
    // A host that reads its M115 takes this description.
    CHECK(find_firmware_by_report(reported_name(*d)) == &f);
  }
}
