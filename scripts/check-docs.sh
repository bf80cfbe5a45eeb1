#!/usr/bin/env bash
# Checks that the developer guide names only what exists (ctest runs it; by
# hand: scripts/check-docs.sh [SOURCE_DIR] [PAGE...]). The code moves while
# the pages stay: a renamed file or class makes this fail, not a reader.
#
# In every `code span` of the pages:
#  * a path (`lib/serial/sender/src/sender.cpp`, `tools/gc-send/`) exists; a short
#    one (`core/line.hpp`, `serial/sender/sender.cpp`) exists under the library's
#    include or source folders (a wing's: lib/serial/sender/); a bare file name (`stage.hpp`) somewhere in
#    the sources; spans with a placeholder (<name>, NAME) or a blank are
#    commands or patterns and are skipped, and so are absolute paths
#    (`/dev/serial/by-id/`) and build trees (`build-asan/`), which are
#    not the repository's;
#  * a type (`PrintControl`) is defined: class, struct, enum or using;
#  * `Type::member` names a member the type's sources mention;
#  * a call (`gcode_tool()`, `reads_state()`) names a function that exists;
#  * a tool (`gc-send`) has its folder under tools/.
# A page names what it makes up on purpose (a recipe's example files) in a
# comment, <!-- check-docs: new fan_cap FanCap -->: spans holding one of
# those words are not looked up.
# Every relative link [text](page.md) outside fenced blocks points at a file. And the parts table
# of docs/writing-a-tool.md names every header of the library.
set -euo pipefail

root=$(cd "${1:-$(dirname "$0")/..}" && pwd)
shift || true
pages=("$@")
cd "$root"
# Every page of docs/: the developer guide and the tools' pages, whose
# examples and file names must stay as real as the guide's.
if [ ${#pages[@]} -eq 0 ]; then
  pages=(docs/*.md)
fi

# Where code lives (the front end may sit in lib/ or in cli/).
code_dirs=()
for d in lib cli tools tests/support tests/unit tests/cli tests/consistency cmake; do [ -d "$d" ] && code_dirs+=("$d"); done
search_dirs=()
for d in lib cli tools tests scripts cmake docs man bench fuzz examples; do [ -d "$d" ] && search_dirs+=("$d"); done
failures=0
fail() {
  echo "check-docs: $1" >&2
  failures=$((failures + 1))
}

path_exists() {
  local p=${1%/} base
  [ -e "$p" ] && return 0
  for base in lib/include/gcode lib/src cli/include/gcode cli/src; do
    [ -e "$base/$p" ] && return 0
  done
  # cli/src/tool.cpp for a short "cli/tool.cpp"
  [ -e "cli/src/${p#cli/}" ] && return 0
  # gc-send's wings: "serial/sender/sender.hpp", "serial/sender/sender.cpp", "serial/sender/"
  if [[ $p == serial/* ]]; then
    local wing=${p#serial/}
    wing=${wing%%/*}
    [ -e "lib/serial/$wing/include/gcode/$p" ] && return 0
    [ -e "lib/serial/$wing/src/${p#serial/"$wing"/}" ] && return 0
  fi
  return 1
}

# The sources read once into one file each: a look-up a span greps one file
# instead of walking the tree (904 spans took 17 s).
sources=$(mktemp)
build_files=$(mktemp)
trap 'rm -f "$sources" "$build_files"' EXIT
find "${code_dirs[@]}" -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) -exec cat {} + >"$sources"
find "${code_dirs[@]}" -type f \( -name '*.cmake' -o -name 'CMakeLists.txt' \) -exec cat {} + >"$build_files"

defined_type() {
  grep -qE "(class|struct|enum class|enum|using|namespace)[[:space:]]+$1\b" "$sources"
}

has_member() {
  local type=$1 member=$2
  grep -qF "$type::$member" "$sources" && return 0
  # A member declared in the type's header.
  local f
  for f in $(grep -rlE "(class|struct|enum class)[[:space:]]+$type\b" "${code_dirs[@]}" --include='*.hpp'); do
    grep -qE "\b$member\b" "$f" && return 0
  done
  return 1
}

function_exists() {
  grep -qE "\b$1[[:space:]]*\(" "$sources" "$build_files"
}

checked=0
for page in "${pages[@]}"; do
  [ -f "$page" ] || {
    fail "$page: no such page"
    continue
  }
  dir=$(dirname "$page")
  declare -A looked_up=()  # a span named again on the page is looked up once
  made_up=$(grep -oE '<!-- check-docs: new [^>]*-->' "$page" | sed -E 's/<!-- check-docs: new //; s/ *-->//' | tr '\n' ' ' || true)
  # Code spans, outside fenced blocks (those hold commands and sketches).
  while IFS= read -r span; do
    checked=$((checked + 1))
    [ -n "${looked_up[$span]+set}" ] && continue
    looked_up[$span]=1
    skip=false
    for word in $made_up; do [[ $span == *"$word"* ]] && skip=true; done
    $skip && continue
    case $span in
      /* | build* | *' '* | *'<'* | *NAME* | *'*'* | *'$'* | *'{'* | *'='* | *'"'* | *"'"* | *...* | -*) continue ;;
    esac
    if [[ $span =~ ^gc-[a-z-]+$ ]]; then
      [ -d "tools/$span" ] || fail "$page: \`$span\`: no tools/$span/"
    elif [[ $span =~ / || $span =~ \.(hpp|cpp|sh|cmake|md|1|txt)$ ]]; then
      if [[ $span =~ / ]]; then
        path_exists "$span" || fail "$page: \`$span\`: no such file or folder"
      elif [ -z "$(find "${search_dirs[@]}" -name "$span" -print -quit)" ]; then
        fail "$page: \`$span\`: no file of that name"
      fi
    elif [[ $span =~ ^([A-Z][A-Za-z0-9]*)::(~?[A-Za-z_][A-Za-z0-9_]*)(\(\))?$ ]]; then
      has_member "${BASH_REMATCH[1]}" "${BASH_REMATCH[2]#\~}" || fail "$page: \`$span\`: no such member"
    elif [[ $span =~ ^([a-z_][A-Za-z0-9_]*\.)?([A-Za-z_][A-Za-z0-9_]*)\(\)$ ]]; then
      function_exists "${BASH_REMATCH[2]}" || fail "$page: \`$span\`: no such function"
    elif [[ $span =~ ^[A-Z][A-Za-z0-9]*[a-z][A-Za-z0-9]*$ ]]; then
      defined_type "$span" || fail "$page: \`$span\`: no such type"
    fi
  done < <(awk '/^```/ { fence = !fence; next } !fence' "$page" | grep -oE '`[^`]+`' | tr -d '`')
  # Relative links.
  while IFS= read -r target; do
    target=${target%%#*}
    [ -z "$target" ] && continue
    [ -e "$dir/$target" ] || fail "$page: link ($target): no such file"
  # (Not in fenced blocks, indented ones in lists too: a lambda's "[](...)"
  # in a sketch is not a link.)
  done < <(awk '/^ *```/ { fence = !fence; next } !fence' "$page" | grep -oE '\]\([^)]+\)' |
    sed -E 's/^\]\(//; s/\)$//' | grep -vE '^(https?:|mailto:|#)')
done

# The parts list is complete: every header, by its stem.
parts=docs/writing-a-tool.md
headers=0
if [ -f "$parts" ]; then
  declare -A named=()  # the page's spans, read once
  while IFS= read -r word; do named[$word]=1; done < <(grep -oE '`[A-Za-z0-9_]+(\.hpp)?`' "$parts" | tr -d '`' |
    sed 's/\.hpp$//')
  while IFS= read -r header; do
    headers=$((headers + 1))
    stem=${header##*/}
    stem=${stem%.hpp}
    [ -n "${named[$stem]+set}" ] || fail "$parts: the parts table does not name $header: add \`$stem\` to its room's row"
  done < <(find lib/include/gcode lib/serial/*/include/gcode cli/include/gcode -mindepth 2 -name '*.hpp' 2>/dev/null | sort)
fi

if [ "$failures" -gt 0 ]; then
  echo "check-docs: $failures names in the guide do not exist (rename them in the page, or the page is out of date)" >&2
  exit 1
fi
echo "check-docs: ${#pages[@]} pages, $checked code spans: every path, type and function named exists;" \
  "the parts table names all $headers headers"
