#!/usr/bin/env bash
# Every test and section name can be printed when it fails. Catch2's console
# reporter wraps a name at 79 columns and indents its continuation lines to
# just after the name's first ": "; Debian's compiled Catch2 (built with
# assertions) aborts when that indent reaches the width, so a failure in
# such a test printed nothing but an assertion of Catch2's own. A test name
# is printed at column 0, a section at column 2: the first ": " has to start
# before column 75 in both (a section: 2 + 74 + 2 < 79).
# usage: test_names.sh SOURCE_DIR TEST_PROGRAM...
set -euo pipefail
source_dir=$1
shift
limit=75
failures=0

# index() is 1-based: ": " starting at column c (0-based) has index c + 1.
too_late() { awk -v limit="$limit" -v what="$1" '{ p = index($0, ": "); if (p > limit) { print "FAIL: " what ": first \": \" at column " p - 1 ": " $0; bad = 1 } } END { exit bad }'; }

for program in "$@"; do
  # Catch2 2.x exits with the number of names it listed.
  names=$("$program" --list-test-names-only) || true
  if [ -z "$names" ]; then
    echo "FAIL: $program listed no test" >&2
    failures=$((failures + 1))
  fi
  too_late "$(basename "$program")" <<<"$names" || failures=$((failures + 1))
  # ctest splits a discovered name at ';': the halves match no test and fail.
  if grep -n ';' <<<"$names" | sed "s#^#FAIL: $(basename "$program"): a ';' in the name: #" | grep .; then
    failures=$((failures + 1))
  fi
done
# Sections are not listed by the programs: read their literal names.
grep -rhoE 'SECTION\("([^"\\]|\\.)*"' "$source_dir/tests" | sed -E 's/^SECTION\("//; s/"$//' |
  too_late "section" || failures=$((failures + 1))

if [ "$failures" -ne 0 ]; then
  echo "rename them: the first \": \" earlier (or none), and no ';'" >&2
  exit 1
fi
echo "test names: every first \": \" before column $limit"
