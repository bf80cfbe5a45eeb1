#include "gcode/serial/journal/input_hash.hpp"

namespace gcode::serial {

bool InputHash::fed(std::string_view bytes) {
  hash_.update(bytes);
  if (hash_.bytes() - checkpointed_ < kCheckpointBytes) return false;
  checkpointed_ = hash_.bytes();
  return true;
}

void InputHash::printed(std::string_view part, std::uint64_t check_at) {
  const std::uint64_t at = hash_.bytes();
  if (check_at > at && check_at <= at + part.size()) {
    const auto head = static_cast<std::size_t>(check_at - at);
    hash_.update(part.substr(0, head));
    check_ = hash_.digest();
    part.remove_prefix(head);
  }
  hash_.update(part);
}

void InputHash::printed_end(std::string_view ahead, std::uint64_t check_at, bool read_through) {
  if (check_at == 0) check_ = PrefixHash().digest();
  if (check_at > hash_.bytes() && read_through) {
    PrefixHash check;
    check.copy_from(hash_);
    check.update(ahead.substr(0, static_cast<std::size_t>(check_at - hash_.bytes())));
    check_ = check.digest();
  }
  checkpointed_ = hash_.bytes();
}

}  // namespace gcode::serial
