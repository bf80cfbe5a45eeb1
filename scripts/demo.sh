#!/usr/bin/env bash
# The main job on the built-in default: installs what is missing, builds, and
# runs the bundled example print through the tools.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
build/bin/gc-layers examples/cube.gcode
