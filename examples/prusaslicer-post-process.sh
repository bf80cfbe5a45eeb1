#!/bin/sh
# PrusaSlicer / SuperSlicer / OrcaSlicer post-processing hook.
#
# Print Settings > Output options > Post-processing scripts:
#   /path/to/gcode-tools/examples/prusaslicer-post-process.sh
#
# The slicer calls the script with the path of the G-code it just wrote (a
# temporary file); each tool rewrites it in place, atomically, and only when it
# succeeded. A non-zero exit makes the slicer report the error and keep nothing.
set -eu
file="$1"
# A pause for a colour change before layer 12 (edit to taste; see man gc-pause-at).
gc-pause-at --before-layer 12 --method M600 -i "$file"
