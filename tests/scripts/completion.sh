#!/usr/bin/env bash
# The generated bash completions work in bash: each is sourced and asked to
# complete as bash would on TAB (COMP_WORDS/COMP_CWORD, then the function
# `complete` registered). For every tool:
#   "gc-x --<TAB>"            exactly the long options its --help declares
#   "gc-x --vers<TAB>"        --version
#   "gc-x --e-mode r<TAB>"    relative (any option with listed choices), also "--e-mode=r"
#   "gc-x -o <dir>/pa<TAB>"   the file (any option whose value is a file)
#   "gc-x --layers <TAB>"     nothing (a number is not a file)
#   "gc-x <dir>/pa<TAB>"      the file, where the tool reads FILE, also after a flag (-q)
# usage: completion.sh COMPLETIONS_DIR BIN_DIR TOOL...
set -euo pipefail
completions=$1 bin=$2
shift 2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
touch "$dir/part.gcode"
failures=0 checks=0

fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# complete TOOL WORD... : the replies for the last word, one a line, sorted.
complete_words() {
  local tool=$1
  shift
  COMP_WORDS=("$tool" "$@")
  COMP_CWORD=$#
  COMP_LINE="$tool $*"
  COMP_POINT=${#COMP_LINE}
  COMPREPLY=()
  local fn
  fn=$(complete -p "$tool" | sed -n 's/.*-F \([^ ]*\) .*/\1/p')
  "$fn" "$tool" "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD-1]}"
  printf '%s\n' "${COMPREPLY[@]}" | sed '/^$/d' | sort
}

expect() {  # expect WHAT EXPECTED ACTUAL
  checks=$((checks + 1))
  [ "$2" = "$3" ] || fail "$1: expected [$(echo $2)] got [$(echo $3)]"
}

for tool in "$@"; do
  script=$completions/$tool
  [ -f "$script" ] || { fail "$tool: no completion at $script"; continue; }
  # shellcheck disable=SC1090
  source "$script"
  complete -p "$tool" >/dev/null || { fail "$tool: sourcing registered nothing"; continue; }
  help=$("$bin/$tool" --help)
  declared=$(printf '%s\n' "$help" | sed -n 's/^  \(-[^ ]*\).*/\1/p' | tr ',' '\n' | sed 's/{.*//' | grep '^--' | sort -u)
  expect "$tool --<TAB>" "$declared" "$(complete_words "$tool" --)"
  expect "$tool --vers<TAB>" "--version" "$(complete_words "$tool" --vers)"
  # (grep -c, not -q, in a pipeline: -q stops reading at the first match, the
  # writer may then die of SIGPIPE, and pipefail fails the whole test.)
  if printf '%s\n' "$declared" | grep -xc -- --e-mode >/dev/null; then
    expect "$tool --e-mode r<TAB>" "relative" "$(complete_words "$tool" --e-mode r)"
    expect "$tool --e-mode=<TAB>" "absolute
auto
relative" "$(complete_words "$tool" --e-mode = '')"
  fi
  if printf '%s\n' "$declared" | grep -xc -- --output >/dev/null; then
    expect "$tool -o DIR/pa<TAB>" "$dir/part.gcode" "$(complete_words "$tool" -o "$dir/pa")"
  fi
  if printf '%s\n' "$declared" | grep -xc -- --layers >/dev/null; then
    expect "$tool --layers <TAB>" "" "$(complete_words "$tool" --layers '')"
  fi
  if printf '%s\n' "$help" | grep -c "^Usage: $tool \[OPTIONS\] \[FILE\]" >/dev/null; then
    expect "$tool DIR/pa<TAB>" "$dir/part.gcode" "$(complete_words "$tool" "$dir/pa")"
    expect "$tool -q DIR/pa<TAB> (a flag takes no value)" "$dir/part.gcode" "$(complete_words "$tool" -q "$dir/pa")"
  fi
done
echo "completion: $checks checks over $# tools, $failures failed"
[ "$failures" -eq 0 ]
