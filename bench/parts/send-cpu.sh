#!/usr/bin/env bash
# gc-send's own CPU time per line while it prints (a print farm runs many on
# one small host): the large file's lines 20001 on (printing, past the start
# code) to gc-virtual-printer, another process, through a pseudo-terminal at
# 250000 baud. Two runs: real moves at a time scale (the printer sets the
# pace, as in a print) and instant moves (the link sets it, gc-send --no-pace:
# the most lines a second gc-send is asked for). Figure: gc-send's user + system time (GNU
# time) over the lines sent, in microseconds a line, and its peak RSS.
#
# Runs under bench/run.sh, or alone: GC_BIN=build/bin GC_BENCH_FILE=F bench/parts/send-cpu.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${GC_BIN:-$root/build/bin}
if [ -n "${GC_BENCH_LIB:-}" ]; then
  # shellcheck source=../measure.sh
  . "$GC_BENCH_LIB"
else
  gc_row() { :; }
fi
lines=${GC_SEND_CPU_LINES:-4000}
scale=${GC_SEND_CPU_SCALE:-5}
tmp=$(mktemp -d "${GC_BENCH_TMP:-/tmp}/send-cpu.XXXXXX")
vp=
trap '[ -n "$vp" ] && kill "$vp" 2>/dev/null; rm -rf "$tmp"' EXIT
sed -n "20001,$((20000 + lines))p" "$GC_BENCH_FILE" >"$tmp/slice.gcode"
sent=$(sed -e 's/;.*//' -e 's/[[:space:]]*$//' -e '/^$/d' "$tmp/slice.gcode" | wc -l)

# Prints "cpu_seconds wall_seconds rss_kb" of one gc-send run; $1: printer
# options, $2: gc-send's.
run_once() {
  local link=$tmp/printer t0 t1
  rm -f "$link"
  # shellcheck disable=SC2086
  "$bin/gc-virtual-printer" -q --link "$link" --heat-rate 100000 $1 &
  vp=$!
  for _ in $(seq 500); do [ -e "$link" ] && break; sleep 0.01; done
  t0=$(date +%s%N)
  # shellcheck disable=SC2086
  XDG_STATE_HOME=$tmp /usr/bin/time -f "%U %S %M" -o "$tmp/time" "$bin/gc-send" -q $2 --port "$link" "$tmp/slice.gcode" \
    2>"$tmp/err" || { cat "$tmp/err" "$tmp/time" >&2; return 1; }
  t1=$(date +%s%N)
  kill "$vp"
  wait "$vp" 2>/dev/null || true
  vp=
  awk -v w="$(((t1 - t0) / 1000000))" '{ printf "%.3f %.3f %d\n", $1 + $2, w / 1000, $3 }' "$tmp/time"
}

for mode in "real moves, time scale $scale" "instant moves, --no-pace"; do
  case $mode in
    real*) printer="--time-scale $scale" send="" ;;
    # --no-pace: gc-send's pacer would hold moves back to the time they take.
    *) printer="--instant-moves" send="--no-pace" ;;
  esac
  read -r cpu wall rss <<<"$(run_once "$printer" "$send")"
  us=$(awk -v c="$cpu" -v n="$sent" 'BEGIN { printf "%.1f", c * 1e6 / n }')
  echo "gc-send, $mode: $sent commands in $wall s, CPU $cpu s (user + system) = $us us a line, peak RSS $rss kB"
  gc_row "gc-send CPU, $mode" - "$(awk -v n="$sent" -v w="$wall" 'BEGIN { printf "%.4f", n / w / 1e6 }')" "$rss" \
    "$us us of CPU a line (user + system), 250000 baud pty"
done
