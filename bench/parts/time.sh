#!/usr/bin/env bash
# gc-layers --time on the large file: the layer table with the print-time
# estimate (planner model with look-ahead) per layer. Target: >= 100 MB/s.
# Also plain gc-layers for comparison (what --time costs on top of the table),
# and peak RSS on the large file and on its first half (memory stays flat).
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
tool=$GC_BIN/gc-layers
gc_bench_input time

gc_measure "$out" "$tool" "$in"
plain_mbs=$(gc_rate "$in_bytes" "$GC_SECONDS" 1e6)
plain_cpu_mbs=$(gc_rate "$in_bytes" "$GC_CPU_SECONDS" 1e6)
for args in "--time" "--time --json"; do
  # shellcheck disable=SC2086
  gc_measure "$out" "$tool" $args "$in"
  secs=$GC_SECONDS rss=$GC_RSS_KB cpu=$GC_CPU_SECONDS
  # shellcheck disable=SC2086
  GC_BENCH_RUNS=1 gc_measure /dev/null "$tool" $args "$half"
  rss_half=$GC_RSS_KB
  mbs=$(gc_rate "$in_bytes" "$secs" 1e6)
  cpu_mbs=$(gc_rate "$in_bytes" "$cpu" 1e6)
  ratio=$(awk -v a="$mbs" -v c="$GC_CAT_MBS" 'BEGIN { printf "%.0f%%", 100 * a / c }')
  echo "gc-layers $args: $(gc_rate "$in_bytes" 1 1e6) MB in ${secs} s = $mbs MB/s (plain gc-layers $plain_mbs MB/s; of cat $ratio)"
  echo "  CPU time ${cpu} s = $cpu_mbs MB/s of CPU (plain gc-layers $plain_cpu_mbs MB/s of CPU)"
  echo "  $(grep -m1 'print time' "$out" || grep -o -m1 '"time": "[^"]*"' "$out")"
  echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
  gc_row "gc-layers $args" "$mbs" "$(gc_rate "$in_lines" "$secs" 1e6)" "$rss / $rss_half" \
    "target >= 100 MB/s; $cpu_mbs MB/s of CPU; plain gc-layers $plain_mbs MB/s"
done
rm -f "$out" "$half"
