#!/usr/bin/env bash
# CPack's Debian packages, checked with dpkg-deb as a packager would:
#   gcode-tools: every tool of the build, its man page (gzip'd, as Debian
#     wants it) and completion, and a
#     Depends that names the package of every shared library the tools load
#     (found with ldd and dpkg -S, not from a list);
#   unpacked into a scratch root (dpkg-deb -x), its tools run;
#   gcode-tools-dev: the headers, libgcode.a and the CMake package, depending
#     on the -dev packages its headers and link line need.
# usage: package.sh BUILD_DIR TOOL...
set -euo pipefail
build=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0 checks=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
check() { checks=$((checks + 1)); }

if ! cpack --config "$build/CPackConfig.cmake" -B "$work" >"$work/cpack.log" 2>&1; then
  cat "$work/cpack.log" >&2
  echo "package: cpack failed" >&2
  exit 1
fi
tools_deb=$(ls "$work"/gcode-tools_*.deb)
dev_deb=$(ls "$work"/gcode-tools-dev_*.deb)
dpkg-deb -I "$tools_deb" >"$work/tools.info"
dpkg-deb -c "$tools_deb" | awk '{print $NF}' >"$work/tools.files"
dpkg-deb -c "$dev_deb" | awk '{print $NF}' >"$work/dev.files"
depends=$(dpkg-deb -f "$tools_deb" Depends)
dev_depends=$(dpkg-deb -f "$dev_deb" Depends)
echo "gcode-tools Depends: $depends"
echo "gcode-tools-dev Depends: $dev_depends"

# The package that owns a library path (usrmerge: /lib and /usr/lib are one).
owner() {
  local path=$1
  dpkg -S "$path" 2>/dev/null || dpkg -S "/usr$path" 2>/dev/null || dpkg -S "${path#/usr}" 2>/dev/null || true
}

declare -A owner_of
for tool in "$@"; do
  for want in "./usr/bin/$tool" "./usr/share/man/man1/$tool.1.gz" "./usr/share/bash-completion/completions/$tool"; do
    check
    grep -qx -- "$want" "$work/tools.files" || fail "gcode-tools lacks $want"
  done
  for lib in $(ldd "$build/bin/$tool" | awk '$2 == "=>" && $3 ~ /^\// {print $3}'); do
    # (Asked once a library: dpkg -S reads the whole database each time,
    # 30 of the script's 40 s when asked for every tool.)
    [ -n "${owner_of[$lib]+set}" ] || owner_of[$lib]=$(owner "$lib" | head -n1 | cut -d: -f1)
    pkg=${owner_of[$lib]}
    [ -n "$pkg" ] || continue
    check
    # (grep -c, not -q, in a pipeline: -q stops reading at the first match, the
    # writer may then die of SIGPIPE, and pipefail fails the whole test.)
    printf '%s\n' "$depends" | tr ',' '\n' | sed 's/^ *//; s/ .*//' | grep -xc -- "$pkg" >/dev/null ||
      fail "$tool loads $lib (package $pkg), which gcode-tools does not depend on"
  done
done
check
grep -q '^ Package: gcode-tools$' "$work/tools.info" || fail "the tools package is not named gcode-tools"

for want in ./usr/include/gcode/version.hpp ./usr/include/gcode/cli/tool.hpp ./usr/include/gcode/pipeline/pipeline.hpp; do
  check
  grep -qx -- "$want" "$work/dev.files" || fail "gcode-tools-dev lacks $want"
done
for pattern in '/libgcode\.a$' '/libgcode_cli\.a$' '/cmake/gcode-tools/gcode-toolsConfig\.cmake$' '/cmake/gcode-tools/gcode-tools-targets\.cmake$'; do
  check
  grep -q -- "$pattern" "$work/dev.files" || fail "gcode-tools-dev has nothing matching $pattern"
done
for dep in libfmt-dev libre2-dev libcli11-dev libstb-dev libxxhash-dev; do
  check
  printf '%s\n' "$dev_depends" | grep -c -- "$dep" >/dev/null || fail "gcode-tools-dev does not depend on $dep"
done
check
if grep -q '^./usr/include/' "$work/tools.files"; then fail "headers in the tools package"; fi

# Unpacked into a scratch root, the packaged tools run and the pages render.
dpkg-deb -x "$tools_deb" "$work/root"
for page in "$work"/root/usr/share/man/man1/*.1.gz; do
  check
  warnings=$(zcat "$page" | groff -man -ww -z 2>&1) || fail "groff failed on the packaged $(basename "$page")"
  [ -z "$warnings" ] || fail "the packaged $(basename "$page"): groff warns: $warnings"
done
for tool in "$@"; do
  check
  [ "$("$work/root/usr/bin/$tool" --version)" = "$("$build/bin/$tool" --version)" ] || fail "the packaged $tool does not run"
done

echo "package: $checks checks over $# tools, $failures failed"
[ "$failures" -eq 0 ]
