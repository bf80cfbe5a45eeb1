#!/usr/bin/env bash
# Pacing against a printer faster than gc-send's motion model (issue 23 §1):
# the virtual printer's speed-factor makes its moves F times faster than the
# file's feed rates say, and does not tell gc-send. For each factor, one run
# paced (the default) and one with --no-pace, on the same 0.2 mm pieces:
# planner starved (% of the print) and commands per printer second.
# Target: paced starves no more than unpaced and runs within 5 % of its rate.
#
#   bench/pace-table.sh [BUILD_BIN] [FIXTURE]     (about a minute)
# GC_PACE_LINES (lines of the subdivided file, default 3000), GC_PACE_SCALE
# (virtual printer time scale, default 5), GC_PACE_FACTORS ("1 1.25 2 10"),
# GC_PACE_PRINTER (more virtual printer options, e.g. advanced-ok) and
# GC_PACE_OPTS (more gc-send options for both runs, e.g. --flow advanced-ok).
set -euo pipefail
bin=${1:-build/bin}
fixture=${2:-tests/fixtures/prusa_cube_0.2_mk3s_rel_zhop.gcode}
lines=${GC_PACE_LINES:-3000}
scale=${GC_PACE_SCALE:-5}
factors=${GC_PACE_FACTORS:-1 1.25 2 10}
printer=${GC_PACE_PRINTER:+,$GC_PACE_PRINTER}
more=${GC_PACE_OPTS:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# From the first layer on (the start code's heating is not what is measured).
"$bin/gc-subdivide" --max 0.2 "$fixture" >"$tmp/all.gcode"
awk -v n="$lines" '/^;LAYER_CHANGE/ { on = 1 } on && k++ < n' "$tmp/all.gcode" >"$tmp/pieces.gcode"
{ echo "G28"; echo "G90"; echo "M83"; cat "$tmp/pieces.gcode"; } >"$tmp/in.gcode"

# "starved_percent commands_per_printer_second" of one run.
one() {
  local factor=$1 opts=$2 err
  err=$("$bin/gc-send" $opts $more --port "virtual:time-scale=$scale,heat-rate=100000,speed-factor=$factor$printer" \
    "$tmp/in.gcode" 2>&1 >/dev/null) || { echo "gc-send failed: $err" >&2; return 1; }
  echo "$err" | awk -v scale="$scale" '
    /summary:/ { for (i = 1; i <= NF; i++) {
                   if ($i == "lines" && !n) n = $(i + 1) + 0
                   if ($i == "time" && !t) t = $(i + 1) + 0 } }
    /planner starved/ { for (i = 1; i <= NF; i++) if ($i == "starved") s = $(i + 1) }
    END { printf "%s %.0f\n", s, (t > 0 ? n / (t * scale) : 0) }'
}

echo "gc-send pacing: $(wc -l <"$tmp/in.gcode") lines (gc-subdivide --max 0.2 of $(basename "$fixture")), time scale $scale${GC_PACE_PRINTER:+, printer $GC_PACE_PRINTER}${more:+, gc-send $more}"
echo "| printer speed vs model | paced: starved | paced: commands/s | --no-pace: starved | --no-pace: commands/s | rate paced/unpaced |"
echo "|---|---|---|---|---|---|"
for f in $factors; do
  read -r ps pr < <(one "$f" "")
  read -r us ur < <(one "$f" "--no-pace")
  ratio=$(awk -v a="$pr" -v b="$ur" 'BEGIN { printf "%.0f %%", (b > 0 ? 100 * a / b : 0) }')
  echo "| ${f}x | $ps | $pr | $us | $ur | $ratio |"
done
