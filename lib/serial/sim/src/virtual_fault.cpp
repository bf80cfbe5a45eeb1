#include "gcode/serial/sim/virtual_fault.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace gcode::serial {

namespace {

double number_in(std::string_view what, std::string_view text) {
  double v = 0;
  auto res = std::from_chars(text.data(), text.data() + text.size(), v);
  if (res.ec != std::errc() || res.ptr != text.data() + text.size() || !std::isfinite(v) || v < 0)
    throw std::invalid_argument(fmt::format("virtual printer fault: {} '{}' is not a number >= 0", what, text));
  return v;
}

}  // namespace

ScheduledFault parse_scheduled_fault(std::string_view text) {
  ScheduledFault f;
  std::size_t at = text.find('@');
  if (at == std::string_view::npos)
    throw std::invalid_argument(fmt::format("virtual printer fault '{}' needs a moment: @line=N, @time=S or @layer=N",
                                            text));
  std::string_view what = text.substr(0, at);
  std::string_view when = text.substr(at + 1);
  std::size_t eq = what.find('=');
  std::string_view kind = what.substr(0, eq);
  if (kind == "reset" && eq == std::string_view::npos) {
    f.kind = ScheduledFault::Kind::Reset;
  } else if ((kind == "drop" || kind == "drop-reset") && eq != std::string_view::npos) {
    f.kind = kind == "drop" ? ScheduledFault::Kind::Drop : ScheduledFault::Kind::DropReset;
    f.seconds = number_in("drop seconds", what.substr(eq + 1));
  } else {
    throw std::invalid_argument(
        fmt::format("virtual printer fault '{}': expected reset, drop=SECONDS or drop-reset=SECONDS before @", what));
  }
  eq = when.find('=');
  std::string_view trigger = when.substr(0, eq);
  if (eq == std::string_view::npos)
    throw std::invalid_argument(fmt::format("virtual printer fault moment '{}' needs a value", when));
  if (trigger == "line") f.trigger = ScheduledFault::Trigger::Line;
  else if (trigger == "time") f.trigger = ScheduledFault::Trigger::Time;
  else if (trigger == "layer") f.trigger = ScheduledFault::Trigger::Layer;
  else throw std::invalid_argument(fmt::format("virtual printer fault moment '{}': expected line, time or layer", trigger));
  f.at = number_in(trigger, when.substr(eq + 1));
  return f;
}

GreetingForm parse_greeting_form(std::string_view text) {
  if (text == "start") return GreetingForm::Start;
  if (text == "nul") return GreetingForm::NulStart;
  if (text == "twice") return GreetingForm::Twice;
  if (text == "external") return GreetingForm::ExternalReset;
  if (text == "cut") return GreetingForm::CutLine;
  throw std::invalid_argument(
      fmt::format("virtual printer greeting '{}': expected start, nul, twice, external or cut", text));
}

bool FaultSchedule::take_if(ScheduledFault& fault, bool (*due)(const ScheduledFault&, double, double), double a,
                            double b) {
  for (auto it = faults_.begin(); it != faults_.end(); ++it) {
    if (!due(*it, a, b)) continue;
    fault = *it;
    faults_.erase(it);
    return true;
  }
  return false;
}

bool FaultSchedule::take_after_command(long long number, int started_layer, ScheduledFault& fault) {
  return take_if(
      fault,
      [](const ScheduledFault& f, double n, double layer) {
        // (A host that numbers on after a reset may jump past N.)
        if (f.trigger == ScheduledFault::Trigger::Line) return n >= 0 && n >= f.at;
        return f.trigger == ScheduledFault::Trigger::Layer && layer > 0 && f.at == layer;
      },
      static_cast<double>(number), started_layer);
}

double FaultSchedule::next_time() const {
  double t = std::numeric_limits<double>::infinity();
  for (const ScheduledFault& f : faults_)
    if (f.trigger == ScheduledFault::Trigger::Time) t = std::min(t, f.at);
  return t;
}

bool FaultSchedule::take_due(double now, ScheduledFault& fault) {
  return take_if(
      fault, [](const ScheduledFault& f, double t, double) { return f.trigger == ScheduledFault::Trigger::Time && f.at <= t; },
      now, 0);
}

}  // namespace gcode::serial
