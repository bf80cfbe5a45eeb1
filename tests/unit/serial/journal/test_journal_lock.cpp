// One gc-send per journal (gcode/serial/journal/journal_lock.hpp): a second
// lock of the same journal is refused while the first lives, and taken once
// it is gone.
#include <catch2/catch.hpp>

#include <optional>
#include <string>

#include "gcode/serial/journal/journal.hpp"
#include "gcode/serial/journal/journal_lock.hpp"
#include "gcode/serial/link/private_path.hpp"
#include "test_support.hpp"

using namespace gcode::serial;

TEST_CASE("journal lock: a second lock of one journal is refused until the first ends", "[serial][journal_lock]") {
  const std::string journal = gctest::temp_dir() + "/lock/print.journal";
  make_private_folder(journal);
  std::optional<JournalLock> first;
  first.emplace(journal);
  CHECK(first->path() == journal + ".lock");
  CHECK_THROWS_AS(JournalLock(journal), JournalError);
  first.reset();
  CHECK_NOTHROW(JournalLock(journal));
}
