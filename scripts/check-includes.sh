#!/usr/bin/env bash
# Checks the layering of the library by its #include lines (ctest runs it;
# by hand: scripts/check-includes.sh, or --self-test to see it catch a
# planted fault of every kind):
#
#   lib/   libgcode, in rooms (docs/architecture.md, "The one-way rule"):
#          core; pipeline; transform and report; litho, objects and procedural
#   lib/serial/<wing>/   gc-send's room in wings, one library each on top of
#          libgcode: link and protocol; sender and journal on them; control
#          on the sender; sim (the simulated printer) on protocol and link
#          only; job on every wing but sim
#   cli/   libgcode_cli, the command-line front end, on top of all of them
#
#  * a file of a room includes headers of its own room and of the rooms it
#    may use (the table below, the same as docs/architecture.md's) only: so
#    nothing in lib/ includes a gcode/cli/ header, core includes only core,
#    litho and serial do not include each other, and the simulated printer
#    includes no sender, journal, control or job header;
#  * a wing's headers are under its own name (lib/serial/W/include/gcode/serial/W/);
#  * no file in lib/ includes CLI11 (<CLI/...>): the library knows no command line;
#  * the front end lives in cli/ (no lib/include/gcode/cli/, no lib/src/cli/),
#    gc-send's room in its wings (no lib/include/gcode/serial/, no lib/src/serial/);
#  * no include circle: a piece (its .hpp and .cpp together, e.g.
#    core/machine_state, serial/sender/sender) never reaches itself through the pieces it includes;
#  * every "gcode/..." include names a header that exists.
#
#   scripts/check-includes.sh [SOURCE_DIR]
#   scripts/check-includes.sh --self-test
set -euo pipefail

# The rooms and what each may include besides itself (docs/architecture.md).
declare -A uses=(
  [core]=""
  [pipeline]="core"
  [transform]="core pipeline"
  [report]="core pipeline"
  [litho]="core pipeline report"
  [objects]="core pipeline transform report"
  [procedural]="core"
  [serial/link]="core pipeline transform report"
  [serial/protocol]="core pipeline transform report"
  [serial/sender]="core pipeline transform report serial/protocol serial/link"
  [serial/journal]="core pipeline transform report serial/protocol serial/link"
  [serial/control]="core pipeline transform report objects serial/sender serial/protocol serial/link"
  [serial/sim]="core pipeline transform report serial/protocol serial/link"
  [serial/job]="core pipeline transform report objects serial/control serial/journal serial/sender serial/protocol serial/link"
  [cli]="core pipeline transform report litho procedural objects serial/job serial/control serial/journal serial/sender serial/protocol serial/link serial/sim"
)

# Prints "ROOM PATH" for every file of the library and the front end (a
# wing's room is serial/WING; a header under another wing's name than its
# folder's gets a room that is none: serial/FOLDER:NAME).
files_of() {
  local root=$1 path room wing
  while IFS= read -r path; do
    case $path in
      lib/serial/*/include/gcode/serial/*/*)
        wing=${path#lib/serial/}; wing=${wing%%/*}
        room=${path#lib/serial/"$wing"/include/gcode/serial/}; room=${room%%/*}
        if [ "$room" = "$wing" ]; then room=serial/$wing; else room=serial/$wing:$room; fi ;;
      lib/serial/*/src/*) room=${path#lib/serial/}; room=serial/${room%%/*} ;;
      lib/serial/*) room=serial/? ;;
      lib/include/gcode/*/* | lib/src/*/*) room=${path#lib/include/gcode/}; room=${room#lib/src/}; room=${room%%/*} ;;
      cli/include/gcode/cli/* | cli/src/*) room=cli ;;
      *) continue ;;
    esac
    echo "$room $path"
  done < <(cd "$root" && find lib cli -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) 2>/dev/null | sort)
}

# The rooms as awk reads them: "room=uses;room=uses;...".
uses_table() {
  local room table=""
  for room in "${!uses[@]}"; do table+="$room=${uses[$room]};"; done
  echo "$table"
}

check() {
  local root=$1 failures=0 edges list headers
  edges=$(mktemp)
  list=$(mktemp)
  headers=$(mktemp)
  for dir in lib/include/gcode/cli lib/src/cli; do
    if [ -e "$root/$dir" ]; then
      echo "check-includes: $dir/: the command-line front end lives in cli/ (cli/include/gcode/cli/, cli/src/)" >&2
      failures=$((failures + 1))
    fi
  done
  for dir in lib/include/gcode/serial lib/src/serial; do
    if [ -e "$root/$dir" ]; then
      echo "check-includes: $dir/: gc-send's room lives in its wings (lib/serial/WING/include/gcode/serial/WING/, lib/serial/WING/src/)" >&2
      failures=$((failures + 1))
    fi
  done
  files_of "$root" >"$list"
  (cd "$root" && find lib/include/gcode lib/serial/*/include/gcode cli/include/gcode -type f 2>/dev/null |
    sed 's|^.*/include/gcode/||') >"$headers"
  # One pass over every file's include lines (a shell loop a line took
  # seconds): prints the problems to stderr, the includes between pieces to
  # $edges, and the count of problems last.
  local found
  found=$(awk -v root="$root" -v edges="$edges" -v table="$(uses_table)" '
    function problem(text) { print "check-includes: " text > "/dev/stderr"; ++failures }
    BEGIN {
      n = split(table, entries, ";")
      for (i = 1; i <= n; ++i) if (entries[i] != "") {
        eq = index(entries[i], "="); uses[substr(entries[i], 1, eq - 1)] = " " substr(entries[i], eq + 1) " "
      }
    }
    FNR == NR { exists[$0] = 1; next }
    {
      room = $1; path = $2
      if (room ~ /:/) {
        problem(path ": a header of the wing " substr(room, 1, index(room, ":") - 1) " under another wing'\''s name: it belongs in lib/serial/WING/include/gcode/serial/WING/")
        next
      }
      if (!(room in uses)) {
        problem(path ": '\''" room "'\'' is no room of the library (scripts/check-includes.sh, docs/architecture.md)")
        next
      }
      # The piece a file is: room/stem (cli/src/tool.cpp and
      # cli/include/gcode/cli/tool.hpp are cli/tool).
      name = path; sub(/.*\//, "", name); sub(/\.[^.]*$/, "", name)
      from = room "/" name
      number = 0
      while ((getline text < (root "/" path)) > 0) {
        ++number
        if (text !~ /^[ \t]*#[ \t]*include/) continue
        if (text ~ /^[ \t]*#[ \t]*include[ \t]*<CLI\//) {
          if (room != "cli") problem(path ":" number ": includes CLI11; the library knows no command line (cli/ does that)")
          continue
        }
        if (!match(text, /^[ \t]*#[ \t]*include[ \t]*["<]gcode\/[^">]+[">]/)) continue
        target = substr(text, RSTART, RLENGTH); sub(/^[^"<]*["<]gcode\//, "", target); sub(/[">]$/, "", target)
        if (target == "version.hpp") continue  # generated by CMake, includes nothing
        # A room is the first folder of the path, a wing the first two (serial/sender).
        target_room = target; sub(/\/.*/, "", target_room)
        if (target_room == "serial") { target_room = target; sub(/^serial\//, "", target_room); sub(/\/.*/, "", target_room); target_room = "serial/" target_room }
        if (!(target in exists)) { problem(path ":" number ": gcode/" target " does not exist"); continue }
        if (target_room != room && index(uses[room], " " target_room " ") == 0) {
          allowed = uses[room]; gsub(/^ +| +$/, "", allowed)
          problem(path ":" number ": " room " includes gcode/" target ": " room " may use only " \
                  (allowed == "" ? "itself" : allowed) " (docs/architecture.md)")
        }
        to = target; sub(/\.[^.]*$/, "", to); sub(/.*\//, "", to); to = target_room "/" to
        if (to != from) print from " " to > edges
      }
      close(root "/" path)
    }
    END { print failures + 0 }' "$headers" "$list")
  failures=$((failures + found))
  # tsort names the pieces of a circle when it finds one.
  local loops
  if ! loops=$(sort -u "$edges" | tsort 2>&1 >/dev/null); then
    echo "check-includes: an include circle (each piece includes the next; a piece is its .hpp and .cpp):" >&2
    grep -v 'input contains a loop' <<<"$loops" | sed 's/^tsort: /  /' >&2
    failures=$((failures + 1))
  fi
  local pieces
  pieces=$(sort -u "$edges" | wc -l)
  rm -f "$edges" "$list" "$headers"
  if [ "$failures" -gt 0 ]; then
    echo "check-includes: $failures problems" >&2
    return 1
  fi
  echo "check-includes: $(files_of "$root" | wc -l) files, $pieces includes between pieces: every room uses only the rooms below it, no circle"
}

# Plants one fault of every kind in a copy of the sources and expects each to be caught.
self_test() {
  local root=$1 work failures=0
  work=$(mktemp -d)
  trap 'rm -rf "$work"' RETURN
  plant() {  # plant NAME COMMAND...: a fresh copy, the fault, then the check must fail
    local name=$1
    shift
    rm -rf "$work/src"
    mkdir -p "$work/src"
    cp -r "$root/lib" "$root/cli" "$work/src/"
    (cd "$work/src" && "$@")
    if check "$work/src" >/dev/null 2>"$work/out"; then
      echo "check-includes --self-test: not caught: $name" >&2
      failures=$((failures + 1))
    else
      echo "check-includes --self-test: caught $name: $(grep -v 'problems$' "$work/out" | head -n 1)"
    fi
  }
  plant "a library file including a cli/ header" \
    sed -i '1a #include "gcode/cli/tool.hpp"' lib/serial/job/src/send_job.cpp
  plant "a library header including CLI11" \
    sed -i '1a #include <CLI/CLI.hpp>' lib/include/gcode/core/line.hpp
  plant "report including transform, its sibling" \
    sed -i '1a #include "gcode/transform/speed.hpp"' lib/src/report/layer_time.cpp
  plant "core including a higher room" \
    sed -i '1a #include "gcode/pipeline/stage.hpp"' lib/src/core/line.cpp
  plant "litho and serial including each other" \
    sed -i '1a #include "gcode/serial/sender/sender.hpp"' lib/src/litho/image.cpp
  plant "the simulated printer including the sender" \
    sed -i '1a #include "gcode/serial/sender/sender.hpp"' lib/serial/sim/src/virtual_printer.cpp
  plant "the protocol including a wing above it (the journal)" \
    sed -i '1a #include "gcode/serial/journal/journal.hpp"' lib/serial/protocol/include/gcode/serial/protocol/pacer.hpp
  plant "a wing's header under another wing's name" \
    sh -c 'mkdir -p lib/serial/sim/include/gcode/serial/sender && mv lib/serial/sender/include/gcode/serial/sender/sender.hpp lib/serial/sim/include/gcode/serial/sender/'
  plant "gc-send's room back under lib/src/serial/" \
    sh -c 'mkdir -p lib/src/serial && cp lib/serial/link/src/port.cpp lib/src/serial/'
  plant "an include circle inside a wing" \
    sed -i '1a #include "gcode/serial/protocol/flow_control.hpp"' lib/serial/protocol/include/gcode/serial/protocol/protocol.hpp
  plant "an include circle inside core" \
    sed -i '1a #include "gcode/core/machine_state.hpp"' lib/include/gcode/core/arc.hpp
  plant "a front-end header back under lib/" \
    sh -c 'mkdir -p lib/include/gcode/cli && cp cli/include/gcode/cli/tool.hpp lib/include/gcode/cli/'
  plant "an include of a header that does not exist" \
    sed -i '1a #include "gcode/core/no_such_piece.hpp"' lib/src/core/line.cpp
  if check "$root" >/dev/null; then
    echo "check-includes --self-test: the sources themselves pass"
  else
    failures=$((failures + 1))
  fi
  [ "$failures" -eq 0 ]
}

here=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = --self-test ]; then
  self_test "${2:-$here}"
else
  check "${1:-$here}"
fi
