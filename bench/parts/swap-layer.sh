#!/usr/bin/env bash
# gc-swap-layer --repeat of one layer in the middle of the large file: every
# other line passes through the splice stage (byte for byte, or with its Z
# raised after the repeated layer), the repeated layer is read again from the
# file by its byte range. Compared with cat of the same file; peak RSS on the
# large file and on its first half shows memory stays flat.
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
tool=$GC_BIN/gc-swap-layer
gc_bench_input swap-layer
layers=$(grep -c '^;LAYER_CHANGE' "$in")
middle=$((layers / 2))

gc_measure "$out" "$tool" --repeat "$middle" "$in"
secs=$GC_SECONDS cpu=$GC_CPU_SECONDS rss=$GC_RSS_KB
out_bytes=$(stat -c %s "$out")
GC_BENCH_RUNS=1 gc_measure /dev/null "$tool" --repeat "$((middle / 2))" "$half"
rss_half=$GC_RSS_KB
mbs=$(gc_rate "$in_bytes" "$secs" 1e6)
cpu_mbs=$(gc_rate "$in_bytes" "$cpu" 1e6)
ratio=$(awk -v a="$mbs" -v c="$GC_CAT_MBS" 'BEGIN { printf "%.0f%%", 100 * a / c }')
cpu_ratio=$(awk -v a="$cpu_mbs" -v c="${GC_CAT_CPU_MBS:-0}" 'BEGIN { if (c > 0) printf "%.0f%%", 100 * a / c; else print "-" }')
echo "gc-swap-layer --repeat $middle (of $layers layers): $(gc_rate "$in_bytes" 1 1e6) MB in -> $(gc_rate "$out_bytes" 1 1e6) MB out in ${secs} s (CPU ${cpu} s)"
echo "  $mbs MB/s = $ratio of cat (CPU: $cpu_mbs MB/s = $cpu_ratio of cat)"
echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
gc_row "gc-swap-layer --repeat 1 layer" "$mbs" "$(gc_rate "$in_lines" "$secs" 1e6)" "$rss / $rss_half" \
  "CPU $cpu_mbs MB/s = $cpu_ratio of cat"
rm -f "$out" "$half"
