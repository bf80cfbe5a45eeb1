#!/usr/bin/env bash
# Names every header of the library without a unit test of its own (ctest
# runs it; by hand: scripts/check-unit-tests.sh [SOURCE_DIR]). The tests
# mirror the library: the header
#
#   lib/include/gcode/<room>/<piece>.hpp                  tests/unit/<room>/test_<piece>.cpp
#   lib/serial/<wing>/include/gcode/serial/<wing>/<piece>.hpp   tests/unit/serial/<wing>/test_<piece>.cpp
#   cli/include/gcode/cli/<piece>.hpp                     tests/unit/cli/test_<piece>.cpp
#
# A header tested elsewhere on purpose (through another piece's test, or a
# tool's) is named, with where, in tests/unit/untested.txt: one
# "<room>/<piece>  why" a line. An entry whose header went away or that
# has a test file now fails too, so the list only shrinks.
set -euo pipefail

root=$(cd "${1:-$(dirname "$0")/..}" && pwd)
cd "$root"
exceptions=tests/unit/untested.txt
declare -A excused=()
if [ -f "$exceptions" ]; then
  while read -r piece _; do
    [[ -z $piece || $piece == \#* ]] && continue
    excused[$piece]=1
  done <"$exceptions"
fi

failures=0
headers=0
declare -A seen=()
while IFS= read -r header; do
  case $header in
    lib/serial/*) piece=${header#lib/serial/*/include/gcode/} ;;
    lib/include/gcode/*) piece=${header#lib/include/gcode/} ;;
    cli/include/gcode/*) piece=${header#cli/include/gcode/} ;;
  esac
  piece=${piece%.hpp}
  headers=$((headers + 1))
  seen[$piece]=1
  test=tests/unit/${piece%/*}/test_${piece##*/}.cpp
  if [ -n "${excused[$piece]+set}" ]; then
    if [ -f "$test" ]; then
      echo "check-unit-tests: $piece has $test now: take it out of $exceptions" >&2
      failures=$((failures + 1))
    fi
  elif [ ! -f "$test" ]; then
    echo "check-unit-tests: $header has no unit test: $test (or a line in $exceptions saying where it is tested)" >&2
    failures=$((failures + 1))
  fi
done < <(find lib/include/gcode lib/serial/*/include/gcode cli/include/gcode -name '*.hpp' 2>/dev/null | sort)
for piece in "${!excused[@]}"; do
  if [ -z "${seen[$piece]+set}" ]; then
    echo "check-unit-tests: $exceptions names $piece, which is no header of the library" >&2
    failures=$((failures + 1))
  fi
done
if [ "$failures" -gt 0 ]; then
  echo "check-unit-tests: $failures problems" >&2
  exit 1
fi
echo "check-unit-tests: $headers headers: each has tests/unit/<room>/test_<piece>.cpp, or is one of the ${#excused[@]} in $exceptions"
