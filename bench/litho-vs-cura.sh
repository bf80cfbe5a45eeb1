#!/usr/bin/env bash
# gc-litho against conventional slicing, with the time explained by feature
# (issue 43; a benchmark, not a timed test). For the test pictures of
# bench/litho-pictures.sh (large light areas, large dark areas, fine detail, a
# drawn face), flat (100 mm wide) and cylinder (54.8 mm, 60 mm high), gc-litho
# writes the lithophane and its STL; Debian's CuraEngine slices that STL at
# the paper's settings (walls 40 mm/s, 100 % infill at 100 mm/s, 0.45 mm
# lines, 0.2 mm layers, no adhesion) with lines and with concentric infill;
# gc-layers --time-by-feature --no-heat-time times all three with the same
# Marlin limits and splits the layers' time (start and end code left out):
#   walls     WALL-OUTER + WALL-INNER at their nominal speed
#   middle    gc-litho's passes (FILL) / Cura's infill and skin (FILL, SKIN)
#   travel    moves without extrusion, and retraction
#   layer     moves to the next layer's Z
#   accel     what speeding up and slowing down costs below the nominal speeds
# and the ratio of gc-litho's layers to each Cura's. Target: <= 0.70 for both.
#
#   bench/litho-vs-cura.sh [BIN_DIR] [WORK_DIR] [-- GC-LITHO OPTIONS]
#
# BIN_DIR: the built tools (build/bin); WORK_DIR: scratch (a temp dir). Cura's
# slices are kept in WORK_DIR and reused while gc-litho's STL of the plate is
# the same, so a second run in the same WORK_DIR slices nothing.
# PLATES='detail-flat dark-cylinder' runs only those plates (default: all 8).
# Needs: apt-get install -y cura-engine imagemagick; the Cura definitions in
# ../shared/slicer-defs/cura (or SLICER_DEFS).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$(cd "${1:-$here/../build/bin}" && pwd)
work=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
[ "${1:-}" = -- ] && shift
extra=("$@")
defs=${SLICER_DEFS:-}
for d in "$here/../../shared/slicer-defs/cura" "$here/../../../shared/slicer-defs/cura"; do
  [ -z "$defs" ] && [ -f "$d/corpus_marlin.def.json" ] && defs=$(cd "$d" && pwd)
done
for need in CuraEngine convert python3; do
  command -v "$need" >/dev/null || { echo "litho-vs-cura: $need is missing (apt-get install -y cura-engine imagemagick)" >&2; exit 1; }
done
[ -f "${defs:-}/corpus_marlin.def.json" ] || { echo "litho-vs-cura: no Cura definitions found (set SLICER_DEFS)" >&2; exit 1; }
mkdir -p "$work"
cd "$work"
"$here/litho-pictures.sh" .

# The paper's conventional baseline. CuraEngine's command line does not
# evaluate Cura's formulas, so every derived setting is given. The minimum
# layer time is off (gc-litho has none) and there is no skirt (gc-litho
# prints a purge line in its start code, Cura's start code has its own).
cura_settings=(
  -s layer_height=0.2 -s layer_height_0=0.2 -s infill_sparse_thickness=0.2
  -s line_width=0.45 -s wall_line_width=0.45 -s wall_line_width_0=0.45 -s wall_line_width_x=0.45
  -s infill_line_width=0.45 -s skin_line_width=0.45 -s initial_layer_line_width_factor=100
  -s wall_line_count=2 -s wall_thickness=0.9
  -s infill_sparse_density=100 -s infill_line_distance=0.45
  -s speed_print=100 -s speed_infill=100 -s speed_topbottom=100 -s speed_roofing=100
  -s speed_wall=40 -s speed_wall_0=40 -s speed_wall_x=40
  -s speed_travel=150 -s speed_layer_0=20 -s speed_print_layer_0=20 -s speed_travel_layer_0=100
  -s speed_slowdown_layers=1 -s cool_min_layer_time=0 -s adhesion_type=none
  -s material_print_temperature=210 -s material_print_temperature_layer_0=210
  -s material_bed_temperature=60 -s material_bed_temperature_layer_0=60
)

cura() {  # STL PATTERN OUT
  CURA_ENGINE_SEARCH_PATH=$defs CuraEngine slice -j "$defs/corpus_marlin.def.json" "${cura_settings[@]}" \
    -s infill_pattern="$2" -s top_bottom_pattern="$2" -s top_bottom_pattern_0="$2" -l "$1" -o "$3" 2>"$3.log"
}

# One row of the breakdown: walls middle travel layer accel layers (seconds).
breakdown() {
  "$bin/gc-layers" --time-by-feature --no-heat-time --json "$1" | python3 -c '
import json, sys
f = json.load(sys.stdin)["summary"]["time_by_feature"]
walls = sum(s for n, s in f["features"].items() if n.startswith("WALL"))
middle = sum(s for n, s in f["features"].items() if not n.startswith("WALL")) + f["unnamed_s"]
travel = f["travel_s"] + f["retract_s"]
print("%.0f %.0f %.0f %.0f %.0f %.1f" % (walls, middle, travel, f["layer_change_s"], f["acceleration_s"], f["layers_s"]))'
}

printf '| plate | program | walls | middle / infill | travel | layer changes | acceleration | layers | gc-litho / this |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
# Cura's two slices of NAME.stl, unless those of the same STL are there.
slice_both() {  # NAME
  local sum
  sum=$(sha256sum <"$1.stl")
  if [ "$(cat "$1.stl.sliced" 2>/dev/null)" != "$sum" ]; then
    cura "$1.stl" lines "$1-lines.gcode" &
    cura "$1.stl" concentric "$1-concentric.gcode"
    wait
    echo "$sum" >"$1.stl.sliced"
  fi
}

worst_lines=0 worst_concentric=0
for picture in light dark detail portrait; do
  for shape in flat cylinder; do
    name=$picture-$shape
    [ -n "${PLATES:-}" ] && [[ " $PLATES " != *" $name "* ]] && continue
    args=()
    [ "$shape" = cylinder ] && args=(--shape cylinder --height 60)
    "$bin/gc-litho" "$picture.png" "${args[@]}" "${extra[@]}" --stl "$name.stl" -o "$name.gcode" -q
    slice_both "$name"
    read -r w m t l a litho < <(breakdown "$name.gcode")
    echo "| $name | gc-litho | $w s | $m s | $t s | $l s | $a s | $(printf '%.0f' "$litho") s | |"
    for pattern in lines concentric; do
      read -r w m t l a layers < <(breakdown "$name-$pattern.gcode")
      ratio=$(python3 -c "print(f'{$litho / $layers:.2f}')")
      echo "| | Cura $pattern | $w s | $m s | $t s | $l s | $a s | $(printf '%.0f' "$layers") s | $ratio |"
      if [ "$pattern" = lines ]; then
        worst_lines=$(python3 -c "print(max($worst_lines, $ratio))")
      else
        worst_concentric=$(python3 -c "print(max($worst_concentric, $ratio))")
      fi
    done
  done
done
echo
echo "worst gc-litho / Cura: lines $worst_lines, concentric $worst_concentric (target: at most 0.70)"
