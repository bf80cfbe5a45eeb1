# Included by ctest after the discovered Catch tests (TEST_INCLUDE_FILES,
# tests/CMakeLists.txt), in a tree whose timing figures are checked (not
# under the sanitizers, where gctest::kTimingFiguresChecked is false and
# these tests check only exactness, beside the others).
#
# The tests that measure how far ahead of the nozzle gc-send lets moves go
# run with no other test beside them. Their figures (pause now within
# 3.2 mm, pacing as fast as --no-pace) are defined on a host that reads the
# printer's answers in time; a loaded host shifts them by a move (issue 23's
# closing note: 3.214 mm once, beside the sanitizer suite's other tests).
set_tests_properties(
  "cli:gc-send pause now: the nozzle stops within 3.2 mm of the request with 0.2 mm pieces"
  "cli:gc-send pause now: within 3.2 mm on a printer twice as fast as gc-send's model"
  "cli:gc-send pacing: a printer twice as fast that reports ADVANCED_OK is followed, against --no-pace"
  "cli:gc-send pacing: a printer twice as fast without ADVANCED_OK is followed with moves of no length"
  "cli:gc-send pacing: a printer ten times as fast, which the link cannot keep full, is fed as fast as with --no-pace"
  PROPERTIES RUN_SERIAL TRUE)
