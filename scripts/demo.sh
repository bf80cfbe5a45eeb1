#!/usr/bin/env bash
# The main job on the built-in default: installs what is missing, builds, and
# prints the bundled example on the virtual printer: the G-code is cut into
# 0.5 mm pieces (gc-subdivide) and streamed with gc-send's buffer-aware flow
# control to the built-in Marlin model, 100 times faster than real time. It
# ends with gc-send's summary: lines sent, time, link utilisation, resends,
# and what the printer executed.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
port="virtual:time-scale=100"
if [ -x build/bin/gc-subdivide ]; then
  build/bin/gc-subdivide --max 0.5 examples/cube.gcode | build/bin/gc-send --port "$port"
else
  build/bin/gc-send --port "$port" examples/cube.gcode
fi
