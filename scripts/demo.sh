#!/usr/bin/env bash
# The main job on the built-in default: installs what is missing, builds, and
# prints the bundled example on the virtual printer: the G-code is cut into
# 0.2 mm pieces (gc-subdivide) and streamed by gc-send to the built-in Marlin
# model (16-block planner, 4-command queue, 250000 baud), 100 times faster
# than real time. Midway a `pause` is written into gc-send's control FIFO, as
# a person in another terminal would: the rest of the layer runs three times
# faster, the head parks at the back of the bed, and a `resume` a moment
# later brings it back to exactly where it left. It ends with a summary:
# lines sent, the pause's latency in mm and s, the layer it paused at, and
# whether every line was executed once, in order.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
bin=build/bin
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fifo=$work/control.fifo status=$work/status.json log=$work/executed.log
# The example's slicer does not name the bed: an Ender-3's.
$bin/gc-subdivide --max 0.2 examples/cube.gcode |
  $bin/gc-send --port "virtual:time-scale=100,log=$log" --bed 235x235 --control "$fifo" --status-file "$status" &
send=$!
wait_for() {  # a pattern in the status file, for up to 60 s
  for _ in $(seq 6000); do grep -q "$1" "$status" 2>/dev/null && return 0; sleep 0.01; done
  return 1
}
wait_for '"layer": 40,' && echo pause > "$fifo"
wait_for '"state": "paused"' && sleep 2 && echo resume > "$fifo"
wait "$send"
echo
echo "== summary"
field() { sed -n "s/.*\"$1\": \([^,}]*\).*/\1/p" "$status"; }
sent=$(field lines)
echo "lines sent: $sent"
printf 'pause: asked in layer %s, paused before layer %s; the nozzle went on %s mm and %s s (printer time) after the request\n' \
  "$(field last_pause_layer)" "$(field last_paused_before)" "$(field last_pause_mm)" "$(field last_pause_s)"
# The printer's log: every numbered line once, in order, none missing.
awk -F'\t' -v sent="$sent" '$2 >= 0 { if ($2 != ++n) bad = 1 } END {
  if (!bad && n == sent + 0) printf "nothing lost: the printer executed all %d lines once, in order\n", n;
  else { printf "LOST OR REORDERED LINES (%d executed, %d sent)\n", n, sent; exit 1 } }' "$log"
