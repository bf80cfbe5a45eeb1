// The input's hash as gc-send feeds it (gcode/serial/journal/input_hash.hpp):
// a checkpoint due every 64 KB fed, and a resume's check digest taken where
// the old journal's checkpoint is, inside the printed part or a little past it.
#include <catch2/catch.hpp>

#include <string>
#include <string_view>

#include "gcode/serial/journal/input_hash.hpp"

using namespace gcode::serial;

namespace test_input_hash {

std::uint64_t hash_of(std::string_view bytes) {
  PrefixHash h;
  h.update(bytes);
  return h.digest();
}

}  // namespace test_input_hash

TEST_CASE("input hash: a checkpoint is due every 64 KB fed", "[serial][input_hash]") {
  InputHash hash;
  const std::string piece(1000, 'G');
  std::string all;
  int due = 0;
  for (int i = 0; i < 140; ++i) {
    all += piece;
    if (hash.fed(piece)) {
      ++due;
      // The first at 66000 bytes, the next 64 KB on from there.
      CHECK(hash.bytes() == (due == 1 ? 66000u : 132000u));
    }
  }
  CHECK(due == 2);
  CHECK(hash.digest() == test_input_hash::hash_of(all));
}

TEST_CASE("input hash: a resume's check inside the printed part", "[serial][input_hash]") {
  InputHash hash;
  hash.printed("abc", 5);
  hash.printed("defg", 5);
  hash.printed("hij", 5);
  hash.printed_end("klm", 5, true);
  CHECK(hash.check_digest() == test_input_hash::hash_of("abcde"));
  CHECK(hash.bytes() == 10);
  CHECK(hash.digest() == test_input_hash::hash_of("abcdefghij"));
}

TEST_CASE("input hash: a check a little past the printed part, or past the input's end", "[serial][input_hash]") {
  InputHash past;
  past.printed("abcde", 8);
  past.printed_end("fghij", 8, true);
  CHECK(past.check_digest() == test_input_hash::hash_of("abcdefgh"));
  CHECK(past.bytes() == 5);  // what is ahead is hashed on a copy only
  InputHash ended;
  ended.printed("abc", 8);
  ended.printed_end("", 8, false);
  CHECK(ended.check_digest() == 0);
  InputHash none;
  none.printed_end("", 0, true);
  CHECK(none.check_digest() == test_input_hash::hash_of(""));
}

TEST_CASE("input hash: after a resume the checkpoints count from the printed part", "[serial][input_hash]") {
  InputHash hash;
  hash.printed(std::string(70000, 'G'), 0);
  hash.printed_end("", 0, true);
  CHECK_FALSE(hash.fed("G1 X1\n"));
  CHECK(hash.fed(std::string(InputHash::kCheckpointBytes, 'G')));
}
