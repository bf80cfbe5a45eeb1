#!/usr/bin/env bash
# gc-litho: mode 2 (--texture) on the large file, a filter like gc-subdivide
# (every extrusion cut at 0.2 mm, then each piece's F and E rewritten; output
# several times the input, so output MB/s against cat of the same bytes), and
# mode 1 on a 100 mm picture (the time to plan, estimate and write a
# lithophane, and its size). Peak RSS on the large file and its first half:
# memory stays flat.
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
here=$(cd "$(dirname "$0")" && pwd)
tool=$GC_BIN/gc-litho
picture=$here/../../tests/fixtures/images/gradient.png
gc_bench_input litho

args=(--texture "$picture" --projection z --width 220 --center 110,110 -q)
gc_measure "$out" "$tool" "${args[@]}" "$in"
secs=$GC_SECONDS rss=$GC_RSS_KB
out_bytes=$(stat -c %s "$out")
out_lines=$(wc -l <"$out")
GC_BENCH_RUNS=1 gc_measure /dev/null "$tool" "${args[@]}" "$half"
rss_half=$GC_RSS_KB
gc_measure "$GC_BENCH_TMP/litho.cat" cat "$out"
cat_same=$(gc_rate "$out_bytes" "$GC_SECONDS" 1e6)
out_mbs=$(gc_rate "$out_bytes" "$secs" 1e6)
in_mbs=$(gc_rate "$in_bytes" "$secs" 1e6)
ratio=$(awk -v a="$out_mbs" -v c="$cat_same" 'BEGIN { printf "%.0f%%", 100 * a / c }')
echo "gc-litho --texture: $(gc_rate "$in_bytes" 1 1e6) MB in -> $(gc_rate "$out_bytes" 1 1e6) MB out in ${secs} s"
echo "  input $in_mbs MB/s, output $out_mbs MB/s; cat of the same bytes $cat_same MB/s; output/cat = $ratio"
echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
gc_row "gc-litho --texture (output)" "$out_mbs" "$(gc_rate "$out_lines" "$secs" 1e6)" "$rss / $rss_half" \
  "input $in_mbs MB/s; output/cat-of-same-bytes $ratio"
rm -f "$out" "$GC_BENCH_TMP/litho.cat" "$half"

gc_measure "$out" "$tool" "$picture" --width 100
secs=$GC_SECONDS rss=$GC_RSS_KB
out_bytes=$(stat -c %s "$out")
out_lines=$(wc -l <"$out")
echo "gc-litho mode 1, 100 mm plate: $(gc_rate "$out_bytes" 1 1e6) MB ($out_lines lines) in ${secs} s, peak RSS ${rss} kB"
gc_row "gc-litho IMAGE (100 mm plate)" "$(gc_rate "$out_bytes" "$secs" 1e6)" "$(gc_rate "$out_lines" "$secs" 1e6)" "$rss" \
  "planned, estimated and written"
rm -f "$out"
