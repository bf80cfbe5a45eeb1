#!/usr/bin/env bash
# Throughput benchmark: one command, one run, every figure against `cat`.
#
#   bench/run.sh
#
# Builds a Release tree in build-bench (without ccache: every object compiled
# here, from this tree, with the bench's flags), makes bench/data/large.gcode (>= 150 MB
# of real PrusaSlicer G-code, see make-large.sh) and a half-size copy, then
# times, with a warm page cache and the output on the same disk:
#   cat FILE > OUT                       the ceiling the issue names; GNU cat copies
#                                        a file to a file with copy_file_range, in
#                                        the kernel, which no filter can do
#   dd bs=256k (read + write)            the ceiling of a program that reads the
#                                        bytes and writes them: the filters' own
#   gc-layers --extract 1- FILE > OUT    parse, state, layers, write every line
#                                        (and checks OUT is identical to FILE)
#   gc-subdivide, gc-pause-at            as pass-through filters (nothing to split,
#                                        one pause)
#   gc-pause-at | gc-subdivide | gc-speedup   the three as a pipeline (one pause,
#                                        nothing to split, an empty region)
#   parse_bench STAGE FILE > OUT         the same pass piece by piece
# then runs every bench/parts/*.sh (other tools' benchmarks) and prints a
# summary table. Environment: GC_BENCH_RUNS (best of N, default 5),
# GC_BENCH_MB (size of the large file, default 160).
#
# A part is run with GC_BIN (the built tools), GC_BENCH_FILE (the large file),
# GC_CAT_MBS and GC_CAT_CPU_MBS (cat's MB/s in this run, by wall and by CPU
# time), GC_BENCH_TMP (a scratch directory),
# GC_BENCH_LIB (bench/measure.sh, timing helpers); its `gc_row` lines become
# rows of the summary table.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build-bench
data=$here/data
mb=${GC_BENCH_MB:-160}
export GC_BENCH_RUNS=${GC_BENCH_RUNS:-5}

if [ ! -x /usr/bin/time ]; then
  echo "bench: installing GNU time (peak memory figures)" >&2
  if [ "$(id -u)" -eq 0 ]; then apt-get install -y -qq time >/dev/null; else sudo apt-get install -y -qq time >/dev/null; fi
fi
# shellcheck source=bench/measure.sh
source "$here/measure.sh"

echo "== building (Release, $build)"
# An empty launcher overrides one cached or taken from CMAKE_CXX_COMPILER_LAUNCHER;
# CCACHE_DISABLE covers a ccache masquerading as the compiler in PATH.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGCODE_TESTS=OFF -DGCODE_BENCH=ON \
  -DCMAKE_CXX_COMPILER_LAUNCHER= -DCMAKE_C_COMPILER_LAUNCHER= >/dev/null
if ! CCACHE_DISABLE=1 cmake --build "$build" -j"$(nproc)" >"$build/bench-build.log" 2>&1; then
  cat "$build/bench-build.log" >&2
  exit 1
fi
bin=$build/bin

echo "== making the input"
file=$data/large.gcode
half=$data/half.gcode
"$here/make-large.sh" "$file" "$mb"
"$here/make-large.sh" "$half" "$((mb / 2))"
out=$data/out.gcode
tmp=$(mktemp -d "$data/tmp.XXXXXX")
trap 'rm -rf "$tmp" "$out"' EXIT

bytes=$(stat -c %s "$file")
half_bytes=$(stat -c %s "$half")
lines=$("$bin/parse_bench" split "$file" 2>&1 >/dev/null | sed -n 's/.*lines=\([0-9]*\).*/\1/p')
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
echo "file:    $file: $(gc_rate "$bytes" 1 1e6) MB, $lines lines"
echo "half:    $half: $(gc_rate "$half_bytes" 1 1e6) MB (peak memory must not grow with the file)"
echo "machine: $(nproc) x ${cpu:-unknown CPU}, $(uname -sr)"
echo "method:  best of $GC_BENCH_RUNS runs, warm page cache, output to $out"
echo

rows=()
cat_mbs=""
cat_cpu_mbs=""
dd_mbs=""
# bench_one NAME NOTE CMD...: measures CMD on the large file (its last
# argument), once more on the half-size file for memory, and records the row.
bench_one() {
  local name=$1 note=$2
  shift 2
  gc_measure "$out" "$@" "$file"
  local secs=$GC_SECONDS cpu=$GC_CPU_SECONDS rss=$GC_RSS_KB
  GC_BENCH_RUNS=1 gc_measure /dev/null "$@" "$half"
  local rss_half=$GC_RSS_KB
  local mbs cpu_mbs lps ratio
  mbs=$(gc_rate "$bytes" "$secs" 1e6)
  cpu_mbs=$(gc_rate "$bytes" "$cpu" 1e6)
  lps=$(gc_rate "$lines" "$secs" 1e6)
  [ -n "$cat_mbs" ] || cat_mbs=$mbs
  [ -n "$cat_cpu_mbs" ] || cat_cpu_mbs=$cpu_mbs
  ratio=$(awk -v a="$mbs" -v c="$cat_mbs" 'BEGIN { printf "%.0f%%", 100 * a / c }')
  dd_ratio=-
  if [ -n "$dd_mbs" ]; then dd_ratio=$(awk -v a="$mbs" -v c="$dd_mbs" 'BEGIN { printf "%.0f%%", 100 * a / c }'); fi
  cpu_ratio=$(awk -v a="$cpu_mbs" -v c="$cat_cpu_mbs" 'BEGIN { if (a == "-" || c == "-") print "-"; else printf "%.0f%%", 100 * a / c }')
  printf '%-36s %7.3f s %7s MB/s %5s M lines/s %4s of cat %4s of dd | CPU %5s s %7s MB/s | RSS %s kB, half file %s kB\n' \
    "$name" "$secs" "$mbs" "$lps" "$ratio" "$dd_ratio" "$cpu" "$cpu_mbs" "$rss" "$rss_half"
  rows+=("$(printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s' "$name" "$mbs" "$lps" "$ratio" "$dd_ratio" "$cpu_mbs" "$rss/$rss_half" "$note")")
}

echo "== the full pass against cat"
bench_one "cat FILE > OUT" "the ceiling (copy_file_range: the kernel copies)" cat
bench_one "dd bs=256k (read + write)" "the ceiling of a program that reads and writes" "$here/dd-copy.sh"
dd_mbs=$(printf '%s\n' "${rows[1]}" | cut -f2)
bench_one "gc-layers --extract 1- FILE > OUT" "full pass, the target is >= 40% of dd" "$bin/gc-layers" --extract 1-
if cmp -s "$out" "$file"; then
  echo "gc-layers --extract 1-: output identical to the input"
else
  echo "bench: gc-layers --extract 1- changed the file" >&2
  exit 1
fi
bench_one "gc-subdivide --max 1000 (nothing to split)" "pass-through filter" "$bin/gc-subdivide" --max 1000
bench_one "gc-pause-at --before-layer 4500 --park 0,200" "pass-through filter with one pause" "$bin/gc-pause-at" --before-layer 4500 --park 0,200
mv "$out" "$tmp/paused.gcode"
# The three as the suite is used (bash -c: time counts the whole pipeline's CPU).
# shellcheck disable=SC2016
bench_one "gc-pause-at | gc-subdivide | gc-speedup" "the pipeline: one pause, nothing to split, an empty region" \
  bash -c 'set -o pipefail; "$0/gc-pause-at" --before-layer 4500 --park 0,200 "$1" | "$0/gc-subdivide" --max 1000 |
    "$0/gc-speedup" --factor 3 --z-range 100000: -q' "$bin"
if ! cmp -s "$out" "$tmp/paused.gcode"; then
  echo "bench: the pipeline's output is not gc-pause-at's alone" >&2
  exit 1
fi
rm -f "$tmp/paused.gcode"
echo
echo "== the same pass piece by piece (bench/parse_bench)"
bench_one "split (LineReader)" "block reads, lines split in place" "$bin/parse_bench" split
bench_one "split + write (OutputBuffer)" "every line written from its raw bytes" "$bin/parse_bench" copy
bench_one "split + Line::parse" "every word of every line" "$bin/parse_bench" parse
bench_one "  + MachineState" "modes, positions, per-move filament" "$bin/parse_bench" state
bench_one "  + LayerTracker" "markers, layer boundaries, held gaps" "$bin/parse_bench" layers
bench_one "  + write = full pass" "what gc-layers --extract 1- does" "$bin/parse_bench" full
if ! cmp -s "$out" "$file"; then
  echo "bench: parse_bench full changed the file" >&2
  exit 1
fi

shopt -s nullglob
parts=("$here"/parts/*.sh)
if [ ${#parts[@]} -gt 0 ]; then
  export GC_BIN=$bin GC_BENCH_FILE=$file GC_CAT_MBS=$cat_mbs GC_CAT_CPU_MBS=$cat_cpu_mbs GC_BENCH_TMP=$tmp GC_BENCH_LIB=$here/measure.sh
  for part in "${parts[@]}"; do
    echo
    echo "== $(basename "$part")"
    if ! bash "$part" >"$tmp/part.out"; then
      grep -v '^BENCH_ROW' "$tmp/part.out" || true
      echo "bench: $(basename "$part") failed" >&2
      exit 1
    fi
    grep -v '^BENCH_ROW' "$tmp/part.out" || true
    while IFS=$'\t' read -r _ name mbs lps rss note; do
      ratio=- dd_ratio=-
      if [ "$mbs" != "-" ]; then
        ratio=$(awk -v a="$mbs" -v c="$cat_mbs" 'BEGIN { printf "%.0f%%", 100 * a / c }')
        dd_ratio=$(awk -v a="$mbs" -v c="$dd_mbs" 'BEGIN { printf "%.0f%%", 100 * a / c }')
      fi
      rows+=("$(printf '%s\t%s\t%s\t%s\t%s\t-\t%s\t%s' "$name" "$mbs" "$lps" "$ratio" "$dd_ratio" "$rss" "$note")")
    done < <(grep '^BENCH_ROW' "$tmp/part.out" || true)
  done
fi

echo
echo "== summary ($(gc_rate "$bytes" 1 1e6) MB, $lines lines; peak RSS: large file / half file; load average $(cut -d' ' -f1-3 /proc/loadavg))"
echo "(wall: best elapsed time; CPU: best user+system time, steadier when the machine is busy)"
printf '%-44s %8s %9s %7s %7s %8s %15s  %s\n' "pass" "MB/s" "M lines/s" "of cat" "of dd" "CPU MB/s" "peak RSS kB" "note"
for row in "${rows[@]}"; do
  IFS=$'\t' read -r name mbs lps ratio dd_ratio cpu_mbs rss note <<<"$row"
  printf '%-44s %8s %9s %7s %7s %8s %15s  %s\n' "$name" "$mbs" "$lps" "$ratio" "$dd_ratio" "$cpu_mbs" "$rss" "$note"
done
