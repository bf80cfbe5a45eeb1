# Included by ctest after the discovered Catch tests (TEST_INCLUDE_FILES,
# tests/CMakeLists.txt): the order of a fresh tree.
#
# The longest tests start first (COST: ctest's estimate in seconds, the
# order of a fresh tree that has no timings of its own yet). Started in
# definition order they came last, and the suite ended with them running
# alone on an idle machine. Seconds from the sanitizer tree (scripts/test.sh).
set_tests_properties(
  "cli:gc-send --resume through a link drop: before it starts, while it asks the printer, in the way back"
  "cli:gc-send killed inside the way back after a printer reset: --resume makes the way back again"
  "cli:gc-send --resume of a print killed inside its pause block: the rest of the block, parked, an exact return"
  PROPERTIES COST 40)
set_tests_properties(
  "cli:gc-send --resume after kill -9: a reset in the resumed print comes back too"
  "cli:gc-send --resume of a print killed while paused goes back into the pause, the printer kept running or reset"
  "cli:gc-send on Prusa: its own pause (M601) and M600 wait for the user, no timeout however long"
  "cli:gc-pause-at: defaults on every fixture keep moves, restore state, push nothing"
  "cli:gc-send flavours: a FIFO pause and resume on each firmware, every command once and in order"
  "cli:gc-send --resume with the default journal and the journal's file, and a pipeline re-run"
  PROPERTIES COST 15)
