#!/usr/bin/env bash
# `make -C examples` end to end, as a user runs it, into a scratch folder:
# STL made by the recipe -> CuraEngine -> gc-pause-at (colour change) ->
# gc-subdivide -> gc-send on the virtual printer, plus the preview, and the
# lithophane and PrusaSlicer routes (each skipped with a message when its
# tool is not here). Then the products are checked, not just their presence.
# usage: examples.sh SOURCE_DIR BIN_DIR
set -euo pipefail
source=$1 bin=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0 checks=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
expect() { checks=$((checks + 1)); [ "$2" = "$3" ] || fail "$1: expected '$2', got '$3'"; }

if ! make -C "$source/examples" OUT="$out" BIN="$bin/" >"$out/make.log" 2>&1; then
  cat "$out/make.log" >&2
  echo "examples: make failed" >&2
  exit 1
fi
cat "$out/make.log"

expect "facets of the 5-point star" 40 "$(grep -c 'facet normal' "$out/star.stl")"
layers() { "$bin/gc-layers" --json "$1" | sed -n 's/.*"summary": {"layers": \([0-9]*\).*/\1/p'; }
expect "layers CuraEngine wrote" 30 "$(layers "$out/star.gcode")"
expect "layers after the pause and the subdivision" 30 "$(layers "$out/star.print.gcode")"
expect "M600 colour changes" 1 "$(grep -c '^M600' "$out/star.paused.gcode")"
# The change comes after layer 15 (Cura's ;LAYER:14) and before layer 16 (;LAYER:15).
m600=$(grep -n '^M600' "$out/star.paused.gcode" | cut -d: -f1)
l14=$(grep -n '^;LAYER:14$' "$out/star.paused.gcode" | cut -d: -f1)
l15=$(grep -n '^;LAYER:15$' "$out/star.paused.gcode" | cut -d: -f1)
expect "M600 between layers 15 and 16" yes "$([ "$l14" -lt "$m600" ] && [ "$m600" -lt "$l15" ] && echo yes || echo no)"
# One print, or two where PrusaSlicer is installed too (the prusa route).
prints=$(grep -c 'gc-send: summary: ' "$out/make.log" || true)
expect "prints on the virtual printer" yes "$([ "$prints" -ge 1 ] && echo yes || echo no)"
expect "every print went through without a fault" "$prints" \
  "$(grep -c 'gc-send: summary: .* resends 0, errors 0, .* timeouts 0' "$out/make.log")"
expect "nothing lost on the virtual printer" "$prints" "$(grep -c 'bytes lost to overruns 0' "$out/make.log")"
checks=$((checks + 1))
xmllint --noout "$out/star-sheet.svg" || fail "the preview sheet is not valid XML"
expect "layer table rows" 30 "$(grep -cE '^ +[0-9]+ +[0-9]+ ' "$out/star.layers.txt" || true)"
if [ -x "$bin/gc-litho" ]; then
  checks=$((checks + 1))
  [ "$(layers "$out/lithophane.gcode")" -gt 0 ] || fail "the lithophane has no layers"
else
  expect "lithophane skipped" 1 "$(grep -c '^lithophane: skipped' "$out/make.log")"
fi
echo "examples: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
