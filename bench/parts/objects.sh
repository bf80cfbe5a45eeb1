#!/usr/bin/env bash
# gc-objects on the large file (twelve labelled pegs, its layers repeated):
# --exclude of one object (the file is read twice: the table, then the
# filter) and the table alone. Wall and CPU time against cat, and peak RSS
# on the large file and on its first half (memory stays flat).
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_CAT_CPU_MBS,
# GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
tool=$GC_BIN/gc-objects
gc_bench_input objects

for args in "--exclude pegs.stl_7 -q" "-q"; do
  # shellcheck disable=SC2086
  gc_measure "$out" "$tool" $args "$in"
  secs=$GC_SECONDS cpu=$GC_CPU_SECONDS rss=$GC_RSS_KB
  case $args in
    *exclude*) name="gc-objects --exclude (one of 12)" ;;
    *) name="gc-objects (the table)" ;;
  esac
  # shellcheck disable=SC2086
  GC_BENCH_RUNS=1 gc_measure /dev/null "$tool" $args "$half"
  rss_half=$GC_RSS_KB
  mbs=$(gc_rate "$in_bytes" "$secs" 1e6)
  cpu_mbs=$(gc_rate "$in_bytes" "$cpu" 1e6)
  ratio=$(awk -v a="$mbs" -v c="$GC_CAT_MBS" 'BEGIN { printf "%.0f%%", 100 * a / c }')
  cpu_ratio=$(awk -v a="$cpu_mbs" -v c="${GC_CAT_CPU_MBS:--}" 'BEGIN { if (c == "-" || c == 0) print "-"; else printf "%.0f%%", 100 * a / c }')
  echo "gc-objects $args: $(gc_rate "$in_bytes" 1 1e6) MB in ${secs} s = $mbs MB/s ($ratio of cat)"
  echo "  CPU time ${cpu} s = $cpu_mbs MB/s of CPU ($cpu_ratio of cat's CPU rate)"
  echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
  gc_row "$name" "$mbs" "$(gc_rate "$in_lines" "$secs" 1e6)" "$rss / $rss_half" \
    "$ratio of cat; CPU $cpu_mbs MB/s, $cpu_ratio of cat"
done
rm -f "$out" "$half"
