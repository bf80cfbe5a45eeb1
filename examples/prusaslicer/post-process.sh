#!/bin/sh
# PrusaSlicer / SuperSlicer / OrcaSlicer post-processing script (README.md
# beside it says where to enter it). The slicer runs it as
#   $SHELL -c "/path/to/post-process.sh '/tmp/.../part.gcode'"
# with every setting exported as SLIC3R_<KEY>; the tools read the printer's
# bed (SLIC3R_BED_SHAPE), height, retraction and filament diameter from
# there. Each tool rewrites the file in place, atomically and only when it
# succeeded; a nonzero exit makes the slicer report the error and export
# nothing, so a half-done file never reaches the printer.
set -eu
file="$1"
# Colour change before layer PAUSE_LAYER (12 unless the environment says).
gc-pause-at --before-layer "${PAUSE_LAYER:-12}" --method M600 -i "$file"
# The first three layers at half speed.
gc-speedup --factor 0.5 --layers 1-3 -i "$file"
