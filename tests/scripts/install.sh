#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then use it as a user would:
#   - every tool the build defines is in bin/ and runs from there (same
#     --version as the build), with its man page and bash completion (which
#     completes, sourced in bash: tests/scripts/completion.sh);
#   - every installed man page renders with `groff -man -ww -z` without a
#     warning (what `man -l` shows);
#   - a pipeline of installed tools works on the example file;
#   - a small CMake project finds the package (find_package(gcode-tools)),
#     links gcode-tools::gcode, and counts the example's layers as the
#     installed gc-layers does; a second program of it links
#     gcode-tools::gcode_cli (the front end) and answers --version and a
#     usage error as every gc tool does.
# usage: install.sh BUILD_DIR SOURCE_DIR TOOL...
set -euo pipefail
build=$1 source=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
failures=0 checks=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { checks=$((checks + 1)); }

cmake --install "$build" --prefix "$prefix" >/dev/null

for tool in "$@"; do
  check
  [ -x "$prefix/bin/$tool" ] || { fail "$tool not installed in bin/"; continue; }
  [ "$("$prefix/bin/$tool" --version)" = "$("$build/bin/$tool" --version)" ] || fail "$tool --version differs from the build's"
  [ -f "$prefix/share/man/man1/$tool.1" ] || fail "$tool: no man page installed"
  [ -s "$prefix/share/bash-completion/completions/$tool" ] || fail "$tool: no bash completion installed"
done
# Nothing installed that the build does not define.
for path in "$prefix"/bin/*; do
  check
  name=$(basename "$path")
  # (grep -c, not -q, in a pipeline: -q stops reading at the first match, the
  # writer may then die of SIGPIPE, and pipefail fails the whole test.)
  printf '%s\n' "$@" | grep -xc -- "$name" >/dev/null || fail "bin/$name is installed but is no tool of the build"
done

# The installed completions complete the installed tools.
check
bash "$(dirname "$0")/completion.sh" "$prefix/share/bash-completion/completions" "$prefix/bin" "$@" >"$work/completion.log" 2>&1 ||
  { cat "$work/completion.log" >&2; fail "the installed bash completions"; }

for page in "$prefix"/share/man/man1/*.1; do
  check
  warnings=$(groff -man -ww -z "$page" 2>&1) || fail "groff failed on $page"
  [ -z "$warnings" ] || fail "$(basename "$page"): groff warns: $warnings"
done

cube=$source/examples/cube.gcode
check
layers=$("$prefix/bin/gc-subdivide" --max 1 "$cube" | "$prefix/bin/gc-layers" --json - |
  sed -n 's/.*"summary": {"layers": \([0-9]*\).*/\1/p')
direct=$("$prefix/bin/gc-layers" --json "$cube" | sed -n 's/.*"summary": {"layers": \([0-9]*\).*/\1/p')
[ -n "$layers" ] && [ "$layers" -gt 10 ] && [ "$layers" = "$direct" ] ||
  fail "installed pipeline: gc-subdivide | gc-layers gives '$layers' layers, gc-layers alone '$direct'"

# A consumer of the library, built against the installed package only.
mkdir -p "$work/consumer"
cat >"$work/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(count-layers LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(gcode-tools 0.1 REQUIRED)
add_executable(count-layers main.cpp)
target_link_libraries(count-layers PRIVATE gcode-tools::gcode)
add_executable(gc-hello hello.cpp)
target_link_libraries(gc-hello PRIVATE gcode-tools::gcode_cli)
CMAKE
cat >"$work/consumer/hello.cpp" <<'CPP'
// A tool of its own on the front end: the common options, messages and exit statuses.
#include <gcode/cli/tool.hpp>

int main(int argc, char** argv) {
  gcode::cli::FilterOptions options;
  gcode::cli::Tool tool("gc-hello", "gc-hello: says hello");
  tool.add_filter_options(options, gcode::cli::kVerbosity);
  return tool.run(argc, argv, [] { return 0; });
}
CPP
cat >"$work/consumer/main.cpp" <<'CPP'
// Counts the layers of a G-code file with libgcode's pipeline.
#include <fcntl.h>

#include <cstdio>

#include <gcode/pipeline/pipeline.hpp>
#include <gcode/version.hpp>

namespace {
struct LayerCount : gcode::Stage {
  int layers = 0;
  void layer(const gcode::LayerInfo& info, const gcode::MachineState& before, gcode::Emitter& out) override {
    ++layers;
    out.layer(info, before);
  }
};
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  int fd = ::open(argv[1], O_RDONLY);
  if (fd < 0) return 1;
  gcode::LayerMarkers markers;
  gcode::Pipeline pipeline(markers);
  LayerCount count;
  pipeline.add(count);
  pipeline.run(fd);
  std::printf("%s %d\n", gcode::kVersion, count.layers);
  return 0;
}
CPP
check
if cmake -S "$work/consumer" -B "$work/consumer/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
     >"$work/consumer.log" 2>&1 && cmake --build "$work/consumer/build" >>"$work/consumer.log" 2>&1; then
  version=$("$prefix/bin/gc-layers" --version | cut -d' ' -f2)
  got=$("$work/consumer/build/count-layers" "$cube")
  [ "$got" = "$version $direct" ] || fail "consumer says '$got', expected '$version $direct'"
  check
  got=$("$work/consumer/build/gc-hello" --version)
  [ "$got" = "gc-hello $version" ] || fail "the consumer's own tool says '$got' to --version"
  check
  status=0
  "$work/consumer/build/gc-hello" --no-such-option 2>"$work/hello.err" || status=$?
  [ "$status" = 2 ] && grep -q '^gc-hello: .*(see gc-hello --help)$' "$work/hello.err" ||
    fail "the consumer's own tool: a usage error gave status $status and '$(cat "$work/hello.err")'"
else
  cat "$work/consumer.log" >&2
  fail "a project using find_package(gcode-tools) does not build"
fi

echo "install: $checks checks over $# tools, $failures failed"
[ "$failures" -eq 0 ]
