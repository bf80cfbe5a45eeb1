#include "gcode/serial/journal/input_identity.hpp"

#include <sys/stat.h>
#include <xxhash.h>

#include <new>

#include <fmt/format.h>

namespace gcode::serial {

InputIdentity identify_input(const std::string& path, int fd) {
  InputIdentity id;
  id.path = path.empty() ? std::string("-") : path;
  struct stat st{};
  if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    id.regular = true;
    id.size = static_cast<std::uint64_t>(st.st_size);
    id.mtime_ns = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
  }
  return id;
}

PrefixHash::PrefixHash() : state_(XXH3_createState()) {
  if (state_ == nullptr) throw std::bad_alloc();
  XXH3_64bits_reset(state_);
}

PrefixHash::~PrefixHash() { XXH3_freeState(state_); }

void PrefixHash::copy_from(const PrefixHash& other) {
  XXH3_copyState(state_, other.state_);
  bytes_ = other.bytes_;
}

void PrefixHash::update(std::string_view bytes) {
  XXH3_64bits_update(state_, bytes.data(), bytes.size());
  bytes_ += bytes.size();
}

std::uint64_t PrefixHash::digest() const { return XXH3_64bits_digest(state_); }

std::string hash_text(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

}  // namespace gcode::serial
