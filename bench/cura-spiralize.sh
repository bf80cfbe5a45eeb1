#!/usr/bin/env bash
# CuraEngine's spiralize (magic_spiralize) with gc-shape vase's bead and bottom: 0.5 mm lines,
# 0.3 mm layers, 3 bottom layers, one wall, no infill, no adhesion, 1.75 mm filament.
#
#   bench/cura-spiralize.sh MODEL.stl OUT.gcode
#
# Needs Debian's cura-engine and the Cura definitions in ../shared/slicer-defs/cura (or
# SLICER_DEFS); exits 3 when either is missing, so that a benchmark can skip the comparison.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
defs=${SLICER_DEFS:-}
for d in "$here/../../shared/slicer-defs/cura" "$here/../../../shared/slicer-defs/cura"; do
  [ -z "$defs" ] && [ -f "$d/corpus_marlin.def.json" ] && defs=$(cd "$d" && pwd)
done
command -v CuraEngine >/dev/null && [ -f "${defs:-}/corpus_marlin.def.json" ] || exit 3
CURA_ENGINE_SEARCH_PATH=$defs exec CuraEngine slice -j "$defs/corpus_marlin.def.json" \
  -s layer_height=0.3 -s layer_height_0=0.3 -s line_width=0.5 -s wall_line_width=0.5 -s wall_line_width_0=0.5 \
  -s wall_line_width_x=0.5 -s skin_line_width=0.5 -s infill_line_width=0.5 -s initial_layer_line_width_factor=100 \
  -s magic_spiralize=true -s wall_line_count=1 -s bottom_layers=3 -s top_layers=0 -s infill_sparse_density=0 \
  -s adhesion_type=none -s support_enable=false -s center_object=true -s machine_nozzle_size=0.5 \
  -s material_diameter=1.75 -s retraction_enable=true -s smooth_spiralized_contours=true \
  -l "$1" -o "$2"
