#!/usr/bin/env bash
# gc-send against its built-in virtual printer (a Marlin model: link byte
# rate, 128-byte RX buffer, 4-command queue, 16-block planner), with each flow
# mode at 115200 and 250000 baud, time-scaled so a run takes seconds.
#
# Two runs per mode and baud, on a slice of subdivided G-code (gc-subdivide
# --max 0.2 of the large file, or its raw lines if gc-subdivide is missing):
#  * link-bound: moves take no time, so the serial link is the only limit.
#    Figures: link utilisation (bytes on the wire / what the baud rate could
#    carry) and lines per second of printer time. Target: window >= 95 %.
#  * real moves: each move takes length / feed rate. Figure: the fraction of
#    the print during which the planner was empty while lines remained.
# And the window / ping-pong ratio of lines per second.
# Run by bench/run.sh with GC_BIN, GC_BENCH_FILE, GC_CAT_MBS, GC_BENCH_TMP, GC_BENCH_LIB.
set -euo pipefail
# shellcheck source=../measure.sh
. "$GC_BENCH_LIB"
send=$GC_BIN/gc-send
slice=$GC_BENCH_TMP/send-slice.gcode
lines=${GC_SEND_LINES:-6000}
# The model runs on the wall clock: a higher scale is quicker but multiplies
# the host's own wake-up latency (large on a loaded machine). Link-bound runs
# (the utilisation figure) therefore run in real time on the first
# $link_lines lines; runs with real moves at a time scale.
link_lines=${GC_SEND_LINK_LINES:-3000}
scale=${GC_SEND_SCALE:-5}

# Skip the start code (heating, homing): the slice is all printing.
if [ -x "$GC_BIN/gc-subdivide" ]; then
  head -n 200000 "$GC_BENCH_FILE" >"$slice.raw"
  "$GC_BIN/gc-subdivide" --max 0.2 "$slice.raw" >"$slice.sub"
  sed -n "20001,$((20000 + lines))p" "$slice.sub" >"$slice"
  rm -f "$slice.raw" "$slice.sub"
  what="gc-subdivide --max 0.2"
else
  sed -n "20001,$((20000 + lines))p" "$GC_BENCH_FILE" >"$slice"
  what="raw lines"
fi
head -n "$link_lines" "$slice" >"$slice.link"
echo "gc-send: $lines lines ($what) of the large file to the virtual printer, time scale $scale;" \
  "link-bound runs: the first $link_lines lines in real time"

# Prints "utilisation lines_per_printer_second starved_percent" for one run.
run_send() {
  local flow=$1 baud=$2 scale=$3 opts=$4 file=$5 err
  err=$("$send" --flow "$flow" --baud "$baud" \
    --port "virtual:time-scale=$scale,heat-rate=100000,advanced-ok$opts" "$file" 2>&1 >/dev/null) || {
    echo "gc-send failed: $err" >&2
    return 1
  }
  echo "$err" | awk -v scale="$scale" '
    /summary:/ { for (i = 1; i <= NF; i++) {
                   if ($i == "lines" && !n) n = $(i + 1) + 0
                   if ($i == "time" && !t) t = $(i + 1) + 0
                   if ($i == "utilisation") u = $(i + 1) } }
    /starved/  { for (i = 1; i <= NF; i++) if ($i == "starved") s = $(i + 1) }
    END { printf "%s %.0f %s\n", u, (t > 0 ? n / (t * scale) : 0), s }'
}

for baud in 115200 250000; do
  declare -A rate=() rate_real=()
  # auto = advanced-ok here: the virtual printer reports ADVANCED_OK.
  for flow in ping-pong window advanced-ok; do
    read -r util lps _ <<<"$(run_send "$flow" "$baud" 1 ",instant-moves" "$slice.link")"
    read -r _ lps_real starved <<<"$(run_send "$flow" "$baud" "$scale" "" "$slice")"
    rate[$flow]=$lps
    rate_real[$flow]=$lps_real
    echo "  $flow at $baud baud: link-bound $util % of the link, $lps lines/s; real moves $lps_real lines/s, planner empty $starved % of the print"
    gc_row "gc-send $flow $baud baud" - "$lps" - \
      "link $util %; real moves: $lps_real lines/s, planner starved $starved %"
  done
  ratio=$(awk -v a="${rate[window]}" -v b="${rate[ping-pong]}" 'BEGIN { printf "%.2f", a / b }')
  ratio_real=$(awk -v a="${rate_real[window]}" -v b="${rate_real[ping-pong]}" 'BEGIN { printf "%.2f", a / b }')
  echo "  window / ping-pong at $baud baud: ${ratio}x lines/s on a link-bound printer, ${ratio_real}x with real moves"
done
rm -f "$slice" "$slice.link"
