#!/usr/bin/env bash
# Installs what is missing, builds (warnings as errors), runs every test, then
# runs the whole suite again under AddressSanitizer + UndefinedBehaviorSanitizer
# and runs the fuzz targets (the pipeline, the sender) for 20 s each.
#
# Two trees, two compilers: g++ -O3 (what users install) and clang with the
# sanitizers and the fuzzer's coverage, so that every file is checked by both
# compilers' -Werror and the fuzz targets are built from the sanitizer
# tree's objects instead of compiling the library a third time. Line tables
# only (-gline-tables-only) and -O1 there, the test files at -O0
# (tests/CMakeLists.txt): the sanitizers' reports keep file and line, the
# build is lighter (docs/testing.md).
#
# ctest runs 3 x cores slots: a test that keeps a core busy takes three, one
# of gc-send's tests (mostly waiting for the virtual printer) one
# (tests/CMakeLists.txt, PROCESSORS).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc)
slots=$((3 * jobs))

# Ninja where the tree is new: it schedules every object of the build in one
# queue, where make waits for a library before compiling what links it. A
# tree made before keeps its generator (cmake refuses to change it).
generator() {
  if [ ! -f "$1/CMakeCache.txt" ] && command -v ninja >/dev/null; then echo "-GNinja"; fi
}

# lld links the test programs 2 to 3 times faster than GNU ld (under the
# sanitizers unit_tests 2.8 -> 0.9 s): some 40 links a run.
linker=()
if command -v ld.lld >/dev/null; then linker=(-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld); fi

cmake -S . -B build $(generator build) -DCMAKE_BUILD_TYPE=Release -DGCODE_WERROR=ON "${linker[@]}" >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$slots"

CC=clang CXX=clang++ cmake -S . -B build-asan $(generator build-asan) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGCODE_WERROR=ON \
  "${linker[@]}" -DGCODE_SANITIZE=ON -DGCODE_FUZZ=ON "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" >/dev/null
cmake --build build-asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j"$slots"

if [ -x fuzz/run.sh ]; then
  fuzz/run.sh 20 build-asan
fi
