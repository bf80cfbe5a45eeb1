#!/usr/bin/env bash
# gc-speedup on the large file: a region that holds no layer (the pass-through:
# every line parsed, tracked and written back; target >= 40 % of cat, and the
# output must be the input byte for byte), then --factor 3 over the middle half
# of the layers (about a quarter of the lines get an F edit or a marker).
# Wall and CPU time against cat, and peak RSS on the large file and on its
# first half (memory stays flat).
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_CAT_CPU_MBS,
# GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
tool=$GC_BIN/gc-speedup
gc_bench_input speedup
layers=$(grep -c '^;LAYER_CHANGE' "$in")
region="$((layers / 4 + 1))-$((3 * layers / 4))"

for args in "--factor 3 --z-range 100000: -q" "--factor 3 --layers $region"; do
  # shellcheck disable=SC2086
  gc_measure "$out" "$tool" $args "$in"
  secs=$GC_SECONDS cpu=$GC_CPU_SECONDS rss=$GC_RSS_KB
  case $args in
    *z-range*)
      name="gc-speedup, empty region"
      if ! cmp -s "$out" "$in"; then
        echo "bench: gc-speedup with an empty region changed the file" >&2
        exit 1
      fi
      ;;
    *)
      name="gc-speedup, half the layers"
      edited=$(grep -c '; gc-speedup ' "$out" || true)
      ;;
  esac
  # shellcheck disable=SC2086
  GC_BENCH_RUNS=1 gc_measure /dev/null "$tool" $args "$half"
  rss_half=$GC_RSS_KB
  mbs=$(gc_rate "$in_bytes" "$secs" 1e6)
  cpu_mbs=$(gc_rate "$in_bytes" "$cpu" 1e6)
  ratio=$(awk -v a="$mbs" -v c="$GC_CAT_MBS" 'BEGIN { printf "%.0f%%", 100 * a / c }')
  cpu_ratio=$(awk -v a="$cpu_mbs" -v c="${GC_CAT_CPU_MBS:--}" 'BEGIN { if (c == "-" || c == 0) print "-"; else printf "%.0f%%", 100 * a / c }')
  echo "gc-speedup $args: $(gc_rate "$in_bytes" 1 1e6) MB in ${secs} s = $mbs MB/s ($ratio of cat)"
  echo "  CPU time ${cpu} s = $cpu_mbs MB/s of CPU ($cpu_ratio of cat's CPU rate)"
  [ -z "${edited:-}" ] || echo "  $edited lines edited of $in_lines (layers $region of $layers)"
  echo "  peak RSS ${rss} kB (half the input: ${rss_half} kB)"
  gc_row "$name" "$mbs" "$(gc_rate "$in_lines" "$secs" 1e6)" "$rss / $rss_half" \
    "$ratio of cat (target >= 40% empty); CPU $cpu_mbs MB/s, $cpu_ratio of cat"
  unset edited
done
rm -f "$out" "$half"
