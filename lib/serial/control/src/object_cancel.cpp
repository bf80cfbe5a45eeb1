#include "gcode/serial/control/object_cancel.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "gcode/core/line.hpp"
#include "gcode/core/text.hpp"
#include "gcode/report/layer_report.hpp"

namespace gcode::serial {

std::vector<std::string> object_terms(std::string_view text) {
  std::vector<std::string> terms;
  std::string term;
  bool quoted = false;
  auto done = [&] {
    if (!term.empty()) terms.push_back(std::move(term));
    term.clear();
  };
  for (char ch : text) {
    if (ch == '"') {
      quoted = !quoted;
      if (!quoted) done();
    } else if (!quoted && (ch == ' ' || ch == '\t' || ch == ',')) {
      done();
    } else {
      term += ch;
    }
  }
  done();
  return terms;
}

void PrintedObjects::feed(std::string_view bytes) {
  for (std::size_t nl; (nl = bytes.find('\n')) != std::string_view::npos; bytes.remove_prefix(nl + 1)) {
    if (partial_.empty()) {
      read_line(bytes.substr(0, nl));
    } else {
      partial_.append(bytes.substr(0, nl));
      read_line(partial_);
      partial_.clear();
    }
  }
  partial_.append(bytes);
}

const ObjectTracker& PrintedObjects::tracker() {
  if (!partial_.empty()) read_line(partial_);
  partial_.clear();
  return tracker_;
}

// (Cura's meshes end with their layer: a resume at a layer's start stands
// in the last mesh until the next ;MESH: line, a few travels later.)
void PrintedObjects::read_line(std::string_view text) {
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  tracker_.line(Line::parse(text));
}

LiveExcluder::LiveExcluder(ObjectCancel& owner, const Precision& precision, std::uint64_t line_offset,
                           int resumed_layer)
    : owner_(owner), excluder_(precision), line_offset_(line_offset) {
  // The rest of the layer a resume stopped in may be left out (the excluder
  // leaves out only lines of layers); downstream, those lines stay in the
  // pipeline's own count, where the session places them.
  if (resumed_layer > 0) excluder_.start_inside_layer(resumed_layer);
}

void LiveExcluder::line(const TrackedLine& t, Emitter& out) {
  last_line_ = t.raw.number + line_offset_;
  excluder_.line(t, out);
  // An object named by this line is left out from the next one on: the
  // label line itself moves nothing.
  tell_owner();
}

void LiveExcluder::tell_owner() {
  const std::size_t names = excluder_.tracker().names().size();
  if (names <= known_) return;
  owner_.named(*this, known_);
  known_ = names;
}

void LiveExcluder::layer(const LayerInfo& info, const MachineState& before, Emitter& out) {
  excluder_.layer(info, before, out);
}

void ObjectCancel::add_stage(Pipeline& pipeline, std::uint64_t line_offset, int resumed_layer) {
  auto stage = std::make_unique<LiveExcluder>(*this, precision_, line_offset, resumed_layer);
  if (stages_.empty() && primed_) stage->excluder().continue_from(printed_);
  pipeline.add(*stage);
  stages_.push_back(std::move(stage));
  // A resume's objects, known from the printed part, are matched now.
  stages_.back()->tell_owner();
}

bool ObjectCancel::matches(const std::string& term, const ObjectName& n) {
  return term == n.key || term == n.id || iequals(term, n.name);
}

const ObjectCancel::Cancelled* ObjectCancel::cancel_of(const ObjectName& n) const {
  for (const Cancelled& c : cancelled_)
    if (matches(c.term, n)) return &c;
  return nullptr;
}

bool ObjectCancel::is_cancelled(const ObjectName& n) const { return cancel_of(n) != nullptr; }

void ObjectCancel::apply(LiveExcluder& stage, int index, Cancelled& c) {
  const ObjectName& n = stage.excluder().tracker().names()[static_cast<std::size_t>(index)];
  if (!stage.excluder().excluded(index)) stage.excluder().exclude(index);
  if (c.matched) return;
  c.matched = true;
  c.term = n.key;
  c.shown = fmt::format("{} ({})", n.id, n.name);
  update_journal_text();
}

void ObjectCancel::named(LiveExcluder& stage, std::size_t known) {
  const std::vector<ObjectName>& names = stage.excluder().tracker().names();
  for (std::size_t i = known; i < names.size(); ++i)
    for (Cancelled& c : cancelled_)
      if (matches(c.term, names[i])) {
        const bool first = !c.matched;
        apply(stage, static_cast<int>(i), c);
        if (first) c.after_line = stage.last_line();
        diag_.info(fmt::format("object {} ({}): left out ({})", names[i].id, names[i].name, c.source));
      }
}

void ObjectCancel::cancel(std::string_view text) {
  LiveExcluder* stage = current();
  for (const std::string& term : object_terms(text)) {
    if (stage == nullptr) {
      exclude({term}, "cancel object");
      continue;
    }
    const std::vector<ObjectName>& names = stage->excluder().tracker().names();
    int found = -1;
    for (std::size_t i = 0; i < names.size() && found < 0; ++i)
      if (matches(term, names[i])) found = static_cast<int>(i);
    if (found < 0) {
      diag_.warn(0, fmt::format("cancel object {}: no such object so far; it is left out if it appears", term));
      exclude({term}, "cancel object", true);
      continue;
    }
    const ObjectName& n = names[static_cast<std::size_t>(found)];
    if (is_cancelled(n)) {
      diag_.info(fmt::format("cancel object {}: {} ({}) is cancelled already", term, n.id, n.name));
      continue;
    }
    std::size_t kept = 0;
    for (const ObjectName& other : names)
      if (!is_cancelled(other)) ++kept;
    if (kept <= 1) {
      diag_.warn(0, fmt::format("cancel object {}: {} ({}) is the last object left; `cancel` ends the print", term,
                                n.id, n.name));
      continue;
    }
    cancelled_.push_back(Cancelled{term, "cancel object", false, {}, stage->last_line()});
    apply(*stage, found, cancelled_.back());
    const bool printing = stage->excluder().current() == found;
    diag_.info(fmt::format("cancel object {} ({}): left out after input line {} ({})", n.id, n.name,
                           stage->last_line(),
                           printing ? "its block ends there, the print goes on with the next object"
                                    : "its next blocks are not sent"));
  }
}

void ObjectCancel::exclude(const std::vector<std::string>& terms, std::string_view source, bool quiet) {
  for (const std::string& term : terms) {
    if (term.empty()) continue;
    bool known = false;
    for (const Cancelled& c : cancelled_)
      if (c.term == term) known = true;
    if (known) continue;
    cancelled_.push_back(Cancelled{term, std::string(source), false, {}, 0});
    if (!quiet) diag_.info(fmt::format("{} {}: left out when it appears", source, term));
    // Objects the stream knows already (a resume's printed part).
    if (LiveExcluder* stage = current()) {
      const std::vector<ObjectName>& names = stage->excluder().tracker().names();
      for (std::size_t i = 0; i < names.size(); ++i)
        if (matches(term, names[i])) apply(*stage, static_cast<int>(i), cancelled_.back());
    }
  }
  update_journal_text();
}

void ObjectCancel::update_journal_text() {
  journal_text_.clear();
  for (const Cancelled& c : cancelled_) {
    if (!journal_text_.empty()) journal_text_ += '\n';
    journal_text_ += c.term;
  }
}

std::string ObjectCancel::state_of(int index, const ObjectName& n) const {
  if (const Cancelled* c = cancel_of(n)) {
    return c->after_line > 0 ? fmt::format("cancelled after input line {}", c->after_line)
                             : fmt::format("cancelled ({})", c->source);
  }
  const LiveExcluder* stage = current();
  return stage != nullptr && stage->excluder().current() == index ? "printing" : "kept";
}

std::vector<std::string> ObjectCancel::listing() const {
  std::vector<std::string> lines;
  const LiveExcluder* stage = current();
  const std::vector<ObjectName> none;
  const std::vector<ObjectName>& names = stage != nullptr ? stage->excluder().tracker().names() : none;
  lines.push_back(names.empty() ? std::string("objects: none named so far")
                                : fmt::format("objects: {} ({} labels)", names.size(),
                                              dialect_name(stage->excluder().tracker().dialect())));
  for (std::size_t i = 0; i < names.size(); ++i)
    lines.push_back(fmt::format("  {:<4} {:<24} {}", names[i].id, names[i].name, state_of(static_cast<int>(i), names[i])));
  for (const Cancelled& c : cancelled_)
    if (!c.matched) lines.push_back(fmt::format("  {:<4} {:<24} cancelled ({}), not seen yet", "-", c.term, c.source));
  return lines;
}

std::string ObjectCancel::json() const {
  const LiveExcluder* stage = current();
  std::string out = "[";
  if (stage != nullptr) {
    const std::vector<ObjectName>& names = stage->excluder().tracker().names();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (i > 0) out += ", ";
      out += "{\"id\": ";
      append_json_string(out, names[i].id);
      out += ", \"name\": ";
      append_json_string(out, names[i].name);
      out += ", \"state\": ";
      const char* state = is_cancelled(names[i])                     ? "cancelled"
                          : stage->excluder().current() == static_cast<int>(i) ? "printing"
                                                                               : "kept";
      append_json_string(out, state);
      out += "}";
    }
  }
  out += "], \"cancelled\": [";
  bool first = true;
  for (const Cancelled& c : cancelled_) {
    if (!first) out += ", ";
    first = false;
    append_json_string(out, c.matched ? c.shown : c.term);
  }
  return out + "]";
}

std::vector<std::string> ObjectCancel::summary() const {
  std::vector<std::string> lines;
  if (cancelled_.empty()) return lines;
  std::uint64_t dropped = 0, extrusions = 0;
  for (const auto& s : stages_) {
    dropped += s->excluder().dropped_lines();
    extrusions += s->excluder().dropped_extrusions();
  }
  std::string which;
  for (const Cancelled& c : cancelled_) {
    if (!c.matched) continue;
    if (!which.empty()) which += ", ";
    which += c.shown;
  }
  if (!which.empty())
    lines.push_back(fmt::format("objects left out: {}; {} moves not sent ({} extrusions)", which, dropped, extrusions));
  for (const Cancelled& c : cancelled_)
    if (!c.matched) lines.push_back(fmt::format("{} {}: no such object in the print", c.source, c.term));
  return lines;
}

}  // namespace gcode::serial
