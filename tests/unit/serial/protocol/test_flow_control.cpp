// How many lines may be in flight (serial/flow_control.hpp): ping-pong one,
// window by lines and bytes (Marlin keeps one RX slot free), a line longer
// than the buffer alone, auto switching to ADVANCED_OK on its first sign,
// the queue learnt from B and only raised after the first answer.
#include <catch2/catch.hpp>

#include "gcode/serial/protocol/flow_control.hpp"

using gcode::serial::FlowControl;
using gcode::serial::FlowMode;
using gcode::serial::Response;

namespace {

Response ok_with_b(int b) {
  Response r = gcode::serial::parse_response("ok N12 P15 B" + std::to_string(b));
  REQUIRE(r.queue_free == b);
  return r;
}

}  // namespace

TEST_CASE("flow control: mode names both ways", "[serial][flow]") {
  for (FlowMode m : {FlowMode::PingPong, FlowMode::Window, FlowMode::AdvancedOk, FlowMode::Auto})
    CHECK(gcode::serial::parse_flow_mode(gcode::serial::flow_mode_name(m)) == m);
  CHECK(std::string(gcode::serial::flow_mode_name(FlowMode::PingPong)) == "ping-pong");
  CHECK_FALSE(gcode::serial::parse_flow_mode("Window").has_value());
  CHECK_FALSE(gcode::serial::parse_flow_mode("").has_value());
}

TEST_CASE("flow control: ping-pong has one line in flight", "[serial][flow]") {
  FlowControl f(FlowMode::PingPong, 4, 128);
  CHECK(f.may_send(0, 0, 20));
  CHECK_FALSE(f.may_send(1, 20, 1));
  CHECK(f.effective() == FlowMode::PingPong);
}

TEST_CASE("flow control: a window counts lines and bytes, one RX slot kept free", "[serial][flow]") {
  FlowControl f(FlowMode::Window, 4, 128);
  CHECK(f.may_send(3, 100, 27));       // 127 bytes fit in 128
  CHECK_FALSE(f.may_send(3, 100, 28)); // 128 would overrun
  CHECK_FALSE(f.may_send(4, 10, 10));  // the queue is full
  CHECK(f.may_send(0, 0, 500));        // a line longer than the buffer goes alone
  CHECK_FALSE(f.may_send(1, 1, 500));
  CHECK_FALSE(f.ok_numbers_acknowledge());
  // Nonsense sizes are at least one.
  FlowControl tiny(FlowMode::Window, 0, -5);
  CHECK(tiny.queue() == 1);
  CHECK(tiny.rx_buffer() == 1);
  CHECK(tiny.may_send(0, 0, 10));
  CHECK_FALSE(tiny.may_send(1, 0, 0));
}

TEST_CASE("flow control: a window ignores what ADVANCED_OK says about the queue", "[serial][flow]") {
  FlowControl f(FlowMode::Window, 4, 128);
  f.on_ok(ok_with_b(7));
  CHECK(f.queue() == 4);
  CHECK(f.effective() == FlowMode::Window);
  CHECK_FALSE(f.ok_numbers_acknowledge());
}

TEST_CASE("flow control: auto is a window until the firmware shows ADVANCED_OK", "[serial][flow]") {
  FlowControl f(FlowMode::Auto, 4, 128);
  CHECK(f.effective() == FlowMode::Window);
  f.on_ok(gcode::serial::parse_response("ok"));  // a plain ok says nothing
  CHECK(f.effective() == FlowMode::Window);
  f.on_ok(ok_with_b(7));
  CHECK(f.effective() == FlowMode::AdvancedOk);
  CHECK(f.requested() == FlowMode::Auto);
  CHECK(f.ok_numbers_acknowledge());
  FlowControl m115(FlowMode::Auto, 4, 128);
  m115.firmware_has_advanced_ok();
  CHECK(m115.effective() == FlowMode::AdvancedOk);
  CHECK(m115.ok_numbers_acknowledge());
}

TEST_CASE("flow control: the queue is B + 1, learnt once, then only raised", "[serial][flow]") {
  FlowControl f(FlowMode::AdvancedOk, 16, 128);
  CHECK_FALSE(f.ok_numbers_acknowledge());  // until an answer carries the fields
  f.on_ok(ok_with_b(3));  // the acknowledged command still holds its slot
  CHECK(f.queue() == 4);  // replaces the configured guess, even downwards
  CHECK(f.ok_numbers_acknowledge());
  f.on_ok(ok_with_b(1));  // a fuller queue reports less: no shrinking
  CHECK(f.queue() == 4);
  f.on_ok(ok_with_b(7));
  CHECK(f.queue() == 8);
  CHECK(f.may_send(7, 10, 10));
  CHECK_FALSE(f.may_send(8, 10, 10));
}
