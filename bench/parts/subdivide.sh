#!/usr/bin/env bash
# gc-subdivide on the large file: --max 0.2 (the paper's setting, output about
# 7x the input) and --latency 0.25. Output is much larger than input, so the
# figure that matters is output MB/s, compared with `cat` writing the same
# number of bytes (the output file itself). Peak RSS on the large file and on
# its first half shows memory stays flat.
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
tool=$GC_BIN/gc-subdivide
gc_bench_input subdivide

for args in "--max 0.2" "--latency 0.25"; do
  # shellcheck disable=SC2086
  gc_measure "$out" "$tool" $args "$in"
  secs=$GC_SECONDS rss=$GC_RSS_KB
  out_bytes=$(stat -c %s "$out")
  out_lines=$(wc -l <"$out")
  # shellcheck disable=SC2086
  GC_BENCH_RUNS=1 gc_measure /dev/null "$tool" $args "$half"
  rss_half=$GC_RSS_KB
  gc_measure "$GC_BENCH_TMP/subdivide.cat" cat "$out"
  cat_same=$(gc_rate "$out_bytes" "$GC_SECONDS" 1e6)
  in_mbs=$(gc_rate "$in_bytes" "$secs" 1e6)
  out_mbs=$(gc_rate "$out_bytes" "$secs" 1e6)
  ratio=$(awk -v a="$out_mbs" -v c="$cat_same" 'BEGIN { printf "%.0f%%", 100 * a / c }')
  echo "gc-subdivide $args: $(gc_rate "$in_bytes" 1 1e6) MB in -> $(gc_rate "$out_bytes" 1 1e6) MB out ($(gc_rate "$out_lines" 1 1e6) M lines) in ${secs} s"
  echo "  input  $in_mbs MB/s"
  echo "  output $out_mbs MB/s; cat of the same $(gc_rate "$out_bytes" 1 1e6) MB: $cat_same MB/s; output/cat = $ratio"
  echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
  gc_row "gc-subdivide $args (output)" "$out_mbs" "$(gc_rate "$out_lines" "$secs" 1e6)" "$rss / $rss_half" \
    "input $in_mbs MB/s; output/cat-of-same-bytes $ratio"
  rm -f "$out" "$GC_BENCH_TMP/subdivide.cat"
done
rm -f "$half"
