#!/usr/bin/env bash
# gc-litho against conventional slicing (issue 15's comparison; a benchmark,
# not a timed test): for three pictures (ImageMagick's rose: and wizard:, and
# a grey gradient) and both shapes, gc-litho writes the lithophane and its STL;
# Debian's CuraEngine slices that STL at the paper's settings (walls 40 mm/s,
# 100 % infill at 100 mm/s, the same layer height and line width, lines and
# concentric infill); the gc-layers estimator times both (heating left out,
# the same Marlin limits for both) and the table gives the ratio
# gc-litho / Cura over the layers (start and end code left out) and in total.
#
#   bench/litho-vs-cura.sh [BIN_DIR] [WORK_DIR]
#
# BIN_DIR: the built tools (build/bin); WORK_DIR: scratch (a temp dir).
# Needs: apt-get install -y cura-engine imagemagick; the Cura definitions in
# ../shared/slicer-defs/cura (or SLICER_DEFS). Target: ratio <= 0.70.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/bin}
work=${2:-$(mktemp -d)}
defs=${SLICER_DEFS:-$here/../../shared/slicer-defs/cura}
for need in CuraEngine convert python3; do
  command -v "$need" >/dev/null || { echo "litho-vs-cura: $need is missing (apt-get install -y cura-engine imagemagick)" >&2; exit 1; }
done
[ -f "$defs/corpus_marlin.def.json" ] || { echo "litho-vs-cura: no Cura definitions in $defs (set SLICER_DEFS)" >&2; exit 1; }
mkdir -p "$work"
cd "$work"

convert rose: rose.png
convert wizard: wizard.png
convert -size 160x100 gradient:black-white -rotate 90 gradient.png

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

# Seconds from gc-layers --time --json: total and the layers alone.
times() {
  "$bin/gc-layers" --time --no-heat-time --json "$1" | python3 -c '
import json, sys
j = json.load(sys.stdin)
total = j["summary"]["time_s"]
layers = sum(l["time_s"] for l in j["layers"])
count = len(j["layers"])
print(f"{total:.1f} {layers:.1f} {count}")'
}

printf '| picture | shape | layers | gc-litho (layers) | Cura lines | ratio | Cura concentric | ratio | total ratio (lines) |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
for picture in rose wizard gradient; do
  for shape in flat cylinder; do
    name=$picture-$shape
    args=()
    [ "$shape" = cylinder ] && args=(--shape cylinder --height 60)
    "$bin/gc-litho" "$picture.png" "${args[@]}" --stl "$name.stl" -o "$name.gcode" -q
    read -r lt ll layers < <(times "$name.gcode")
    row="| $picture | $shape | $layers | $(printf '%.0f s' "$ll")"
    total_ratio=
    for pattern in lines concentric; do
      CURA_ENGINE_SEARCH_PATH=$defs CuraEngine slice -j "$defs/corpus_marlin.def.json" "${cura_settings[@]}" \
        -s infill_pattern=$pattern -s top_bottom_pattern=$pattern -s top_bottom_pattern_0=$pattern \
        -l "$name.stl" -o "$name-cura-$pattern.gcode" 2>"$name-cura-$pattern.log"
      read -r ct cl _ < <(times "$name-cura-$pattern.gcode")
      row="$row | $(printf '%.0f s' "$cl") | $(python3 -c "print(f'{$ll / $cl:.2f}')")"
      [ -z "$total_ratio" ] && total_ratio=$(python3 -c "print(f'{$lt / $ct:.2f}')")
    done
    echo "$row | $total_ratio |"
  done
done
