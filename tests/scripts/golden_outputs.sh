#!/usr/bin/env bash
# Every tool's output on every fixture is what it was: the SHA-256 of what
# each run below writes to standard output, with its exit status, against
# tests/golden/outputs.txt. A faster path (issue 25: blocks, a lighter
# parse, threads) must change no byte of any output; this says which run
# changed, on which file.
#
# An intended change of output regenerates the list, and the diff of
# outputs.txt goes into the same commit, saying what changed:
#   tests/scripts/golden_outputs.sh build/bin tests/fixtures tests/golden/outputs.txt --update
#
# Runs from the fixtures' folder, each file on standard input or by its
# name only, so no output holds a path of this machine. Release tree only
# (tests/CMakeLists.txt): the figures are g++'s, and the sanitizer tree
# runs every tool on every fixture in other tests.
# usage: golden_outputs.sh BIN_DIR FIXTURES_DIR GOLDEN [--update]
set -euo pipefail
bin=$(cd "$1" && pwd)
fixtures=$2
golden=$(cd "$(dirname "$3")" && pwd)/$(basename "$3")
update=${4:-}
cd "$fixtures"

# Each run: a tool, its options; FILE stands for the fixture's name (the
# file is on standard input as well).
runs=(
  "gc-layers"
  "gc-layers --time"
  "gc-layers --extract 2-3"
  "gc-subdivide --max 0.5"
  "gc-subdivide --latency 0.25"
  "gc-pause-at --before-layer 3"
  "gc-pause-at --before-layer 2,4 --method M600 --bed 220x220"
  "gc-pause-at --z 1.1 --park 10,200"
  "gc-speedup --factor 1.5 --layers 2-3"
  "gc-speedup --factor 0.5 --types PERIMETER,WALL-OUTER --max-flow 8"
  "gc-swap-layer --skip 2 --repeat 3x2"
  "gc-relayer --resume-from-z 1 FILE"
  "gc-relayer --at-z 1 FILE"
  "gc-deform --xyz x+0.1*z y z"
)
# Runs of their own: the lithophane texture on the vases, the shapes.
vase_runs=("gc-litho --texture images/gradient.png --height 10")
shape_runs=(
  "gc-shape helix --diameter 30 --height 5"
  "gc-shape cylinder --diameter 20 --height 3"
  "gc-shape cone --diameter 30 --height 4"
)

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# run FILE RUN: one line "STATUS SHA256 FILE :: RUN".
run() {
  local file=$1 line=$2 status=0
  local words=${line//FILE/$file}
  set -f  # split the run into words, without globbing its '*'
  # shellcheck disable=SC2086
  set -- $words
  set +f
  local tool=$1
  shift
  if [ "$file" = "-" ]; then
    "$bin/$tool" "$@" </dev/null >"$tmp/out" 2>/dev/null || status=$?
  else
    "$bin/$tool" "$@" <"$file" >"$tmp/out" 2>/dev/null || status=$?
  fi
  printf '%s %s %s :: %s\n' "$status" "$(sha256sum <"$tmp/out" | cut -d' ' -f1)" "$file" "$line"
}

for file in *.gcode; do
  for line in "${runs[@]}"; do run "$file" "$line"; done
  case $file in
    *vase*) for line in "${vase_runs[@]}"; do run "$file" "$line"; done ;;
  esac
done >"$tmp/now.txt"
for line in "${shape_runs[@]}"; do run - "$line"; done >>"$tmp/now.txt"

if [ "$update" = "--update" ]; then
  cp "$tmp/now.txt" "$golden"
  echo "golden outputs: $(wc -l <"$golden") runs written to $golden"
  exit 0
fi
if ! diff -u "$golden" "$tmp/now.txt" >"$tmp/diff"; then
  echo "FAIL: outputs differ from $golden (- before, + now: exit status, SHA-256, file, run):" >&2
  grep '^[-+][^-+]' "$tmp/diff" >&2 || true
  echo "an intended change: run this script with --update and commit outputs.txt with it" >&2
  exit 1
fi
echo "golden outputs: $(wc -l <"$golden") runs, every output as it was"
