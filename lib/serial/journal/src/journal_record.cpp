#include "gcode/serial/journal/journal_record.hpp"

#include <charconv>

#include <xxhash.h>

#include <algorithm>

#include <fmt/format.h>

namespace gcode::serial {

namespace {

bool needs_escape(char c) {
  auto u = static_cast<unsigned char>(c);
  return u <= ' ' || u == 0x7f || c == '=' || c == '#' || c == '%';
}

void append_escaped(std::string& out, std::string_view text) {
  for (char c : text) {
    if (needs_escape(c)) {
      out += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

std::optional<std::string> unescape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 2 >= text.size()) return std::nullopt;
    int hi = hex_value(text[i + 1]);
    int lo = hex_value(text[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return out;
}

std::uint32_t check_of(std::string_view payload) {
  return XXH32(payload.data(), payload.size(), 0x6a6f7572u /* "jour" */);
}

}  // namespace

// The index of `key` (items_.size() when it is missing), looked for from
// `hint` on first: the keys of a point, or of a delta, come in the order
// of the full point's.
std::size_t JournalFields::index_of(std::string_view key, std::size_t hint) const {
  const std::size_t size = items_.size();
  for (std::size_t i = std::min(hint, size); i < size; ++i)
    if (items_[i].first == key) return i;
  for (std::size_t i = 0; i < std::min(hint, size); ++i)
    if (items_[i].first == key) return i;
  return size;
}

void JournalFields::set(std::string_view key, std::string_view value) {
  std::size_t i = index_of(key, next_);
  if (i == items_.size()) items_.emplace_back(std::string(key), std::string(value));
  else items_[i].second.assign(value);
  next_ = i + 1;
}

const std::string* JournalFields::find(std::string_view key) const {
  std::size_t i = index_of(key, 0);
  return i < items_.size() ? &items_[i].second : nullptr;
}

std::uint64_t JournalFields::count(std::string_view key) const {
  const std::string* v = find(key);
  std::uint64_t n = 0;
  if (v == nullptr || v->empty()) return 0;
  auto res = std::from_chars(v->data(), v->data() + v->size(), n);
  return res.ec == std::errc() && res.ptr == v->data() + v->size() ? n : 0;
}

std::string JournalFields::get(std::string_view key, std::string_view otherwise) const {
  const std::string* v = find(key);
  return v != nullptr ? *v : std::string(otherwise);
}

bool JournalFields::erase(std::string_view key) {
  auto it = std::find_if(items_.begin(), items_.end(), [&](const auto& kv) { return kv.first == key; });
  if (it == items_.end()) return false;
  items_.erase(it);
  next_ = 0;
  return true;
}

void JournalFields::update(const JournalFields& other) {
  for (const auto& [k, v] : other.items_) set(k, v);
}

JournalFields JournalFields::changed_since(const JournalFields& before) const {
  JournalFields out;
  // Points of one journal hold their keys in the same order: field i of
  // one is field i of the other, but where a key first appeared later.
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const auto& [k, v] = items_[i];
    std::size_t j = before.index_of(k, i);
    if (j == before.items_.size() || before.items_[j].second != v) out.items_.emplace_back(k, v);
  }
  return out;
}

std::string encode_journal_record(const JournalRecord& record) {
  std::string line(1, record.type);
  for (const auto& [k, v] : record.fields.items()) {
    line += ' ';
    append_escaped(line, k);
    line += '=';
    append_escaped(line, v);
  }
  line += fmt::format(" #{:08x}\n", check_of(line));
  return line;
}

std::optional<JournalRecord> decode_journal_record(std::string_view line, RecordProblem* problem) {
  auto fail = [&](RecordProblem p) -> std::optional<JournalRecord> {
    if (problem != nullptr) *problem = p;
    return std::nullopt;
  };
  // " #" and eight hex digits end every record.
  constexpr std::size_t kTail = 10;
  if (line.size() < 1 + kTail || line[line.size() - kTail] != ' ' || line[line.size() - kTail + 1] != '#')
    return fail(RecordProblem::Incomplete);
  std::string_view payload = line.substr(0, line.size() - kTail);
  std::uint32_t check = 0;
  for (char c : line.substr(line.size() - 8)) {
    int h = hex_value(c);
    if (h < 0) return fail(RecordProblem::Incomplete);
    check = check * 16 + static_cast<std::uint32_t>(h);
  }
  if (check != check_of(payload)) return fail(RecordProblem::BadCheck);
  JournalRecord record;
  record.type = payload[0];
  std::string_view rest = payload.substr(1);
  while (!rest.empty()) {
    if (rest[0] != ' ') return fail(RecordProblem::Malformed);
    rest.remove_prefix(1);
    std::size_t end = rest.find(' ');
    std::string_view field = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end);
    std::size_t eq = field.find('=');
    if (eq == std::string_view::npos || eq == 0) return fail(RecordProblem::Malformed);
    auto key = unescape(field.substr(0, eq));
    auto value = unescape(field.substr(eq + 1));
    if (!key || !value) return fail(RecordProblem::Malformed);
    record.fields.set(*key, std::move(*value));
  }
  if (problem != nullptr) *problem = RecordProblem::None;
  return record;
}

}  // namespace gcode::serial
