#!/usr/bin/env bash
# Installs what is missing, builds (warnings as errors), runs every test, then
# runs the whole suite again under AddressSanitizer + UndefinedBehaviorSanitizer
# and runs the fuzz targets (the pipeline, the sender) for 20 s each.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc)

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGCODE_WERROR=ON >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGCODE_WERROR=ON -DGCODE_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j"$jobs"

if [ -x fuzz/run.sh ]; then
  fuzz/run.sh 20
fi
