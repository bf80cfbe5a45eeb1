#!/usr/bin/env bash
# Instructions a line by part of the full pass, under callgrind: a count that
# does not depend on how busy the machine is (bench/run.sh's MB/s do).
#
#   bench/instructions.sh BIN_DIR [FILE]
#
# BIN_DIR holds parse_bench and the tools (a Release build); FILE defaults
# to the first 300000 lines of bench/data/large.gcode (make it with
# bench/run.sh or bench/make-large.sh). Each parse_bench stage and each
# pass-through filter runs once under valgrind --tool=callgrind; a part's
# figure is its stage's count less the stage before it.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:?usage: bench/instructions.sh BIN_DIR [FILE]}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
file=${2:-}
if [ -z "$file" ]; then
  file=$tmp/head.gcode
  head -n 300000 "$here/data/large.gcode" >"$file"
fi
lines=$(wc -l <"$file")

# Prints the instructions CMD... executes, its standard output to /dev/null.
count() {
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$@" >/dev/null 2>"$tmp/cg.err" ||
    { cat "$tmp/cg.err" >&2; return 1; }
  sed -n 's/^==[0-9]*== Collected : //p' "$tmp/cg.err"
}
per_line() { awk -v n="$1" -v l="$lines" 'BEGIN { printf "%.0f", n / l }'; }

echo "file: $file, $lines lines; instructions a line (callgrind)"
previous=0
for stage in split copy parse state layers full; do
  n=$(count "$bin/parse_bench" "$stage" "$file")
  case $stage in
    copy) part=$(per_line $((n - split_n))) base=$split_n ;;
    parse) part=$(per_line $((n - split_n))) base=$n ;;
    split) part=$(per_line "$n") split_n=$n base=$n ;;
    *) part=$(per_line $((n - previous))) base=$n ;;
  esac
  printf '%-8s %6s a line, part %6s\n' "$stage" "$(per_line "$n")" "$part"
  previous=$base
done
for tool in "gc-layers --extract 1-" "gc-subdivide --max 1000" "gc-speedup --factor 3 --z-range 100000: -q"; do
  # shellcheck disable=SC2086
  printf '%-44s %6s a line\n' "$tool" "$(per_line "$(count "$bin"/$tool "$file")")"
done
