#!/usr/bin/env bash
# gc-send recovering from faults: 3000 short moves (gc-subdivide --max 0.2 of
# a bundled PrusaSlicer print, lines 2001-5000) to gc-virtual-printer through
# a pseudo-terminal at 250000 baud, in real time, with moves that take no
# time (the link and the recovery are all that counts). One clean run, then
# runs with 1 % corrupted lines, 0.2 % lost oks, 0.2 % junk lines and 0.2 %
# spurious resend requests (seeds 1 to GC_SEND_FAULT_RUNS, default 3).
# Figures: wall time of each run, faulty / clean, overdue answers and
# timeouts from gc-send's summary, and whether the printer executed every
# line exactly once, in order.
#
# Runs under bench/run.sh, or alone: GC_BIN=build/bin bench/parts/send-faults.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${GC_BIN:-$root/build/bin}
if [ -n "${GC_BENCH_LIB:-}" ]; then
  # shellcheck source=../measure.sh
  . "$GC_BENCH_LIB"
else
  gc_row() { :; }
fi
runs=${GC_SEND_FAULT_RUNS:-3}
tmp=$(mktemp -d "${GC_BENCH_TMP:-/tmp}/send-faults.XXXXXX")
vp=
trap '[ -n "$vp" ] && kill "$vp" 2>/dev/null; rm -rf "$tmp"' EXIT

"$bin/gc-subdivide" --max 0.2 "$root/tests/fixtures/prusa_cube_0.2_mk3s_rel_zhop.gcode" | sed -n 2001,5000p \
  >"$tmp/moves.gcode"
# The commands gc-send sends (no comments, blank lines or M110), for the check.
sed -e 's/;.*//' -e 's/[[:space:]]*$//' -e '/^$/d' "$tmp/moves.gcode" >"$tmp/expected"
echo "gc-send faults: $(wc -l <"$tmp/expected") commands, 0.2 mm pieces, virtual printer on a pty at 250000 baud," \
  "real time, moves take no time"

# Prints "seconds overdue timeouts exact" for one run; $1: extra printer options.
run_once() {
  local link=$tmp/printer log=$tmp/executed.log err=$tmp/err t0 t1 exact
  rm -f "$link"
  # shellcheck disable=SC2086
  "$bin/gc-virtual-printer" -q --link "$link" --log "$log" --instant-moves $1 &
  vp=$!
  for _ in $(seq 500); do [ -e "$link" ] && break; sleep 0.01; done
  t0=$(date +%s%N)
  "$bin/gc-send" --port "$link" "$tmp/moves.gcode" 2>"$err" || { cat "$err" >&2; return 1; }
  t1=$(date +%s%N)
  kill "$vp"
  wait "$vp" 2>/dev/null || true
  vp=
  # Numbered commands only, in the order executed, without the final M400.
  awk -F'\t' '$2 >= 0 { print $7 }' "$log" | sed '$d' >"$tmp/got"
  awk -F'\t' '$2 >= 0 { if ($2 != ++n) bad = 1 } END { exit bad }' "$log" && cmp -s "$tmp/got" "$tmp/expected" &&
    exact=yes || exact=no
  awk -v s="$(((t1 - t0) / 1000000))" -v e="$exact" '/summary:/ {
      for (i = 1; i <= NF; i++) { if ($i == "answers") o = $(i + 1) + 0; if ($i == "timeouts") t = $(i + 1) + 0 }
      printf "%.3f %d %d %s\n", s / 1000, o, t, e }' "$err"
}

read -r clean _ clean_timeouts clean_exact <<<"$(run_once "")"
echo "  clean:  $clean s, timeouts $clean_timeouts, every line once in order: $clean_exact"
worst=0
for seed in $(seq "$runs"); do
  faults="--fault corrupt=0.01 --fault drop-ok=0.002 --fault garbage=0.002 --fault resend=0.002 --fault seed=$seed"
  read -r t overdue timeouts exact <<<"$(run_once "$faults")"
  ratio=$(awk -v a="$t" -v b="$clean" 'BEGIN { printf "%.2f", a / b }')
  worst=$(awk -v a="$ratio" -v b="$worst" 'BEGIN { print (a > b ? a : b) }')
  echo "  faulty (seed $seed): $t s = ${ratio}x clean, overdue answers $overdue, timeouts $timeouts," \
    "every line once in order: $exact"
done
gc_row "gc-send with faults" - - - "3000 pieces at 250000 baud: clean $clean s, worst faulty ${worst}x clean"
