#!/usr/bin/env bash
# Installs the Debian packages gcode-tools needs to build and test, and only
# those that are missing: on a machine that has them all it does nothing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config   # compiler and build
  ninja-build                        # scripts/test.sh: one queue for the whole build
  libcli11-dev libfmt-dev libre2-dev # the library and tools
  libstb-dev                         # gc-litho: picture decoding (stb_image)
  libxxhash-dev                      # gc-send's journal: input hash and record checks
  libmuparser-dev                    # gc-deform: the formulas (muparser)
  libpolyclipping-dev                # gc-shape vase --mesh: polygon offsets (Clipper)
  catch2 nlohmann-json3-dev          # unit and tool tests (JSON reports read back)
  clang libclang-rt-14-dev           # libFuzzer targets (the runtime is only recommended)
  lld                                # scripts/test.sh links with it: 2 to 3 times faster than ld
  librsvg2-bin libxml2-utils         # tests: render and validate SVG
  cura-engine make groff-base        # tests: examples/Makefile's recipe (STL -> G-code), man pages render
  dpkg-dev                           # tests: CPack's .deb dependencies (dpkg-shlibdeps)
  imagemagick                        # tests: gc-litho on ImageMagick's built-in rose: and wizard:
)

missing=()
for p in "${packages[@]}"; do
  # (grep -c, not -q, in a pipeline: -q stops reading at the first match, the
  # writer may then die of SIGPIPE, and pipefail fails the whole test.)
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -c "install ok installed" >/dev/null || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}" >&2
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
