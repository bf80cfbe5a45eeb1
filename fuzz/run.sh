#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz (or BUILD) and
# runs each for SECONDS (default 30):
#  * fuzz_pipeline, the whole streaming pipeline, from a seed corpus: cuts of
#    every fixture (the start, a layer change, the middle, the end) and edge
#    cases (CRLF, no final newline, NUL bytes, a very long line, a lone CR,
#    packed words, checksums), and the kept seeds of fuzz/seeds/pipeline;
#  * fuzz_sender, the printer-reply parser and the sender's state machine,
#    from scripted printer sessions (oks, resends in window and ADVANCED_OK
#    flow, lost oks, busy, heating reports, junk).
# Exits non-zero on a crash, a leak, a sanitizer report or a failed check; the
# input that did it is left in BUILD/artifacts/.
#
#   fuzz/run.sh [SECONDS] [BUILD]
#
# BUILD: a tree already configured with clang and -DGCODE_FUZZ=ON (test.sh's
# sanitizer tree is one): the targets are built there, sharing its objects,
# instead of compiling the library a third time in build-fuzz.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-30}
build=${2:-$root/build-fuzz}
seeds=$root/fuzz/corpus-run/seeds
work=$root/fuzz/corpus-run/work
sender_seeds=$root/fuzz/corpus-run/sender-seeds
sender_work=$root/fuzz/corpus-run/sender-work

if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found (scripts/install-deps.sh installs it)" >&2
  exit 1
fi
if [ $# -ge 2 ]; then
  build=$(cd "$build" && pwd)
  if ! grep -qx 'GCODE_FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
    echo "fuzz: $build is not a tree configured with -DGCODE_FUZZ=ON" >&2
    exit 2
  fi
else
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGCODE_FUZZ=ON \
    -DGCODE_WERROR=ON -DGCODE_TESTS=OFF -DGCODE_BENCH=OFF >/dev/null
fi
cmake --build "$build" -j"$(nproc)" --target fuzz_pipeline fuzz_sender >/dev/null

# Seeds: rebuilt every run so they follow the fixtures, plus the kept ones
# (fuzz/seeds/: inputs the fuzzers once found a fault with, each a unit test too).
rm -rf "$seeds" "$sender_seeds"
mkdir -p "$seeds" "$work" "$sender_seeds" "$sender_work" "$build/artifacts"
cp "$root"/fuzz/seeds/pipeline/* "$seeds"/
if compgen -G "$root/fuzz/seeds/sender/*" >/dev/null; then cp "$root"/fuzz/seeds/sender/* "$sender_seeds"/; fi
for f in "$root"/tests/fixtures/*.gcode; do
  name=$(basename "$f" .gcode)
  size=$(stat -c %s "$f")
  head -c 3000 "$f" >"$seeds/$name.start"
  tail -c 3000 "$f" >"$seeds/$name.end"
  head -c $((size / 2 + 3000)) "$f" | tail -c 3000 >"$seeds/$name.middle"
  # Around the second layer marker of any slicer.
  line=$(grep -n -m2 -E '^;LAYER|^; CHANGE_LAYER|^; layer [0-9]' "$f" | tail -n 1 | cut -d: -f1 || true)
  if [ -n "$line" ]; then
    sed -n "$((line > 40 ? line - 40 : 1)),$((line + 80))p" "$f" >"$seeds/$name.layer"
  fi
done
printf ';LAYER_CHANGE\r\n;Z:0.2\r\nG1 Z.2 F900\r\nG1 X10 Y10 E1.5\r\n;LAYER_CHANGE\r\n;Z:0.4\r\nG1 Z.4\r\nG1 X0 E2\r\n' >"$seeds/crlf"
printf 'G28\nG1 Z0.2\nG1 X10 E1\nG1 Z0.4\nG1 X0 E2' >"$seeds/no-final-newline"
printf 'G1 X1\0Y2 E\0.5\n\0\0\nG1 Z0.3 E1\n;\0comment\n' >"$seeds/nul-bytes"
{ printf 'G1 X1 E1 ; '; head -c 60000 /dev/zero | tr '\0' 'x'; printf '\nG1 Z1\nG1 X2 E2\n'; } >"$seeds/long-line"
printf 'G1 X1\rY2\r\r\nG1 X2 E1\r\r\n\r\n\n' >"$seeds/lone-cr"
printf 'g1x10y5e.5\nG1X-.2Y+3E1e2\nN12 G1 X1 E2*71\nG91\nG1 E-1\nG90\nM83\nG92 E0\nG20\nG1 X1 E.1\nG21\nG2 X10 Y0 I5 J0 E3\nG3 X0 Y0 R5 E4\nG10\nG11\nT1\nM104 S200 T1\n(comment) G1 X5 (inline) E5\n' >"$seeds/packed-and-modes"
printf ';LAYER:0\nG0 Z0.2\nG1 X1 E1\n;LAYER:1\n;LAYER:2\nG0 Z0.6\nG1 X2 E2\n; layer 3, Z = 0.8\nG1 Z0.8\nG1 X3 E3\n; CHANGE_LAYER\n; Z_HEIGHT: 1.0\nG1 Z1\nG1 X4 E4\n' >"$seeds/markers"

# Sender sessions (see fuzz/fuzz_sender.cpp): 9 bytes of configuration
# (flow, queue, RX buffer, line limit, flags, timeout, rounds, commands,
# kinds), then events: \006\000\000 an "ok", \006\007\00N "Resend:" for a line
# N-1 back from the newest, \006\006\000\020\003 "ok N.. P16 B3", \001\000 the
# timer, \006\012\000 busy, \006\014\000 a heating report.
repeat() { local i; for ((i = 0; i < $2; i++)); do printf '%b' "$1"; done; }
ok='\006\000\000' timer='\001\000'
{ printf '\001\003\140\120\000\011\005\047\007'; repeat "$ok" 6; printf '\006\007\003'; repeat "$timer" 3
  repeat "$ok" 20; printf '\006\007\002'; repeat "$timer" 3; repeat "$ok" 30; printf '\006\007\001'
  repeat "$timer" 3; repeat "$ok" 60; } >"$sender_seeds/window-resends"
{ printf '\002\003\140\120\000\011\005\047\007'; repeat '\006\006\000\020\003\006\000\000' 30
  printf '\006\007\001'; repeat "$timer" 3; repeat '\006\006\000\020\003' 40; } >"$sender_seeds/advanced-ok"
{ printf '\000\000\140\120\002\002\002\020\003'; repeat "$ok" 3; repeat '\006\012\000' 4; repeat "$timer" 6
  repeat '\006\014\000' 5; repeat "$ok" 30; } >"$sender_seeds/ping-pong-busy-heating"
{ printf '\001\003\140\040\011\001\000\057\021'; repeat "$ok$timer" 40; repeat "$timer" 20; } >"$sender_seeds/lost-oks"

status=0
run_target() {
  local target=$1 corpus=$2 seed_dir=$3 max_len=$4
  echo "fuzz: $target for ${seconds}s from $(ls "$seed_dir" | wc -l) seeds" >&2
  # Seeds first, then the corpus the fuzzer grows (kept between runs, gitignored).
  (cd "$build/artifacts" && "$build/bin/$target" -max_total_time="$seconds" -max_len="$max_len" -timeout=20 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/" "$corpus" "$seed_dir" \
    2>"$build/$target.log") || {
    local code=$?
    tail -n 60 "$build/$target.log" >&2
    echo "fuzz: $target FAILED (exit $code); reproduce with $build/bin/$target $build/artifacts/<crash-file>" >&2
    return 1
  }
  grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "$build/$target.log" | sed "s/^/fuzz: $target: /" >&2 || true
  echo "fuzz: $target: no crash in ${seconds}s" >&2
}
# Each target is one process on one core: with two cores they run side by
# side, each still for its full SECONDS.
if [ "$(nproc)" -ge 2 ]; then
  run_target fuzz_pipeline "$work" "$seeds" 65536 &
  pipeline=$!
  run_target fuzz_sender "$sender_work" "$sender_seeds" 8192 &
  sender=$!
  wait "$pipeline" || status=1
  wait "$sender" || status=1
else
  run_target fuzz_pipeline "$work" "$seeds" 65536 || status=1
  run_target fuzz_sender "$sender_work" "$sender_seeds" 8192 || status=1
fi
exit $status
