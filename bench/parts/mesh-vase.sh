#!/usr/bin/env bash
# gc-shape vase --mesh on a wavy vase of a million triangles (bench/make_vase_stl 60 1000 500:
# 50 MB of binary STL), against CuraEngine's spiralize of the same mesh with the same bead
# (bench/cura-spiralize.sh), both timed here, best of GC_BENCH_RUNS: CPU seconds (user +
# system), peak RSS, and gc-shape's CPU time over CuraEngine's (the target: at most 0.5).
# Without CuraEngine or its definitions, gc-shape alone.
# Run by bench/run.sh with GC_BIN, GC_BENCH_TMP, GC_BENCH_LIB; alone:
#   GC_BIN=build/bin GC_BENCH_TMP=/tmp GC_BENCH_LIB=bench/measure.sh bench/parts/mesh-vase.sh
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
here=$(cd "$(dirname "$0")" && pwd)
stl=$GC_BENCH_TMP/wavy-1m.stl
out=$GC_BENCH_TMP/wavy-1m.gcode
triangles=$("$GC_BIN/make_vase_stl" 60 1000 500 "$stl")
mb=$(gc_rate "$(stat -c %s "$stl")" 1 1e6)

gc_measure "$out" "$GC_BIN/gc-shape" vase --mesh "$stl"
gc_cpu=$GC_CPU_SECONDS gc_secs=$GC_SECONDS gc_rss=$GC_RSS_KB
echo "gc-shape vase --mesh: $triangles triangles ($mb MB): CPU $gc_cpu s, wall $gc_secs s, peak RSS $gc_rss kB"
note="CPU $gc_cpu s, $triangles triangles"
status=0
"$here/../cura-spiralize.sh" "$stl" "$GC_BENCH_TMP/cura.gcode" 2>/dev/null || status=$?
if [ "$status" -eq 0 ]; then
  gc_measure /dev/null "$here/../cura-spiralize.sh" "$stl" "$GC_BENCH_TMP/cura.gcode"
  ratio=$(awk -v a="$gc_cpu" -v c="$GC_CPU_SECONDS" 'BEGIN { printf "%.2f", a / c }')
  echo "CuraEngine spiralize: CPU $GC_CPU_SECONDS s, wall $GC_SECONDS s, peak RSS $GC_RSS_KB kB"
  echo "gc-shape / CuraEngine CPU time: $ratio (target <= 0.5)"
  note="$note; CuraEngine $GC_CPU_SECONDS s, $GC_RSS_KB kB; ratio $ratio (target <= 0.5)"
elif [ "$status" -eq 3 ]; then
  echo "CuraEngine or its definitions missing: no comparison"
else
  echo "bench: CuraEngine failed on $stl" >&2
  exit 1
fi
gc_row "gc-shape vase --mesh (1 M triangles)" - - "$gc_rss" "$note"
rm -f "$stl" "$out" "$GC_BENCH_TMP/cura.gcode"
