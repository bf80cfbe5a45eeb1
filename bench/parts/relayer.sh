#!/usr/bin/env bash
# gc-relayer --at-z with the large file as both inputs, joined at half its
# height: the old file (standard input) is tracked up to the join and not read
# after it; the new one is indexed up to the join (one pass, by byte range)
# and streamed from there to its end. The output is about as large as the
# input; MB/s are output bytes per second, compared with cat of the input.
# Peak RSS on the large file and on its first half shows memory stays flat.
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
tool=$GC_BIN/gc-relayer
gc_bench_input relayer
# The Z of the layer at half the file's layers (PrusaSlicer's ;Z: comments).
z_at_half() {
  local n
  n=$(grep -c '^;Z:' "$1")
  grep '^;Z:' "$1" | sed -n "$((n / 2))p" | cut -c4-
}
z=$(z_at_half "$in")
z_half=$(z_at_half "$half")
# gc-relayer --at-z Z NEW < OLD, with NEW = OLD = FILE (exec: time measures the tool itself).
# shellcheck disable=SC2016
gc_measure "$out" bash -c 'exec "$0" --at-z "$1" -q "$2" < "$2"' "$tool" "$z" "$in"
secs=$GC_SECONDS cpu=$GC_CPU_SECONDS rss=$GC_RSS_KB
out_bytes=$(stat -c %s "$out")
# shellcheck disable=SC2016
GC_BENCH_RUNS=1 gc_measure /dev/null bash -c 'exec "$0" --at-z "$1" -q "$2" < "$2"' "$tool" "$z_half" "$half"
rss_half=$GC_RSS_KB
mbs=$(gc_rate "$out_bytes" "$secs" 1e6)
cpu_mbs=$(gc_rate "$out_bytes" "$cpu" 1e6)
ratio=$(awk -v a="$mbs" -v c="$GC_CAT_MBS" 'BEGIN { printf "%.0f%%", 100 * a / c }')
cpu_ratio=$(awk -v a="$cpu_mbs" -v c="${GC_CAT_CPU_MBS:-0}" 'BEGIN { if (c > 0) printf "%.0f%%", 100 * a / c; else print "-" }')
echo "gc-relayer --at-z $z FILE < FILE: $(gc_rate "$out_bytes" 1 1e6) MB out in ${secs} s (CPU ${cpu} s)"
echo "  $mbs MB/s = $ratio of cat (CPU: $cpu_mbs MB/s = $cpu_ratio of cat)"
echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
gc_row "gc-relayer --at-z (half, FILE < FILE)" "$mbs" "$(gc_rate "$(wc -l <"$out")" "$secs" 1e6)" "$rss / $rss_half" \
  "output MB/s; CPU $cpu_mbs MB/s = $cpu_ratio of cat"
rm -f "$out" "$half"
