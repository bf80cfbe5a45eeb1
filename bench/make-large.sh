#!/usr/bin/env bash
# Builds a large, real G-code file for the benchmarks, deterministically.
#
#   bench/make-large.sh [OUT] [MIN_MB] [SOURCE]
#
# OUT defaults to bench/data/large.gcode, MIN_MB to 160, SOURCE to a
# PrusaSlicer fixture (100 layers, relative E, z-hop, object labels). The start
# code of SOURCE is written once, then its layers again and again with Z (moves,
# ;Z: comments, the layer-Z comment and Klipper's CURRENT_LAYER) shifted so Z
# keeps rising, until the file has at least MIN_MB megabytes (10^6 bytes), then
# its end code once. Relative extrusion needs no E adjustment. The same inputs
# give the same bytes; an existing OUT of at least MIN_MB is kept.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-$here/data/large.gcode}
min_mb=${2:-160}
src=${3:-$here/../tests/fixtures/prusa_pegs_0.2_klipper_zhop_labels.gcode}
min_bytes=$((min_mb * 1000000))

if [ -f "$out" ] && [ "$(stat -c %s "$out")" -ge "$min_bytes" ]; then
  exit 0
fi
mkdir -p "$(dirname "$out")"

# Where the layers begin (first ;LAYER_CHANGE) and where the end code begins
# (the first line after the last extruding move that is not an acceleration
# or a "; stop printing object" label: the final retract and lift are end code,
# so each copy's own first-layer retract follows the previous copy directly).
first=$(grep -n -m1 '^;LAYER_CHANGE' "$src" | cut -d: -f1)
last_extrusion=$(grep -n -E '^G1 .*X.* E[0-9.]' "$src" | tail -1 | cut -d: -f1)
end=$(awk -v from="$last_extrusion" 'NR > from && !/^(M204 |; )/ { print NR; exit }' "$src")
top_z=$(awk -v to="$end" 'NR < to && /^;Z:/ { z = substr($0, 4) } END { print z }' "$src")
layers=$(awk -v from="$first" -v to="$end" 'NR >= from && NR < to && /^;LAYER_CHANGE/ { n++ } END { print n }' "$src")
head_bytes=$(head -n $((first - 1)) "$src" | wc -c)
body_bytes=$(sed -n "${first},$((end - 1))p" "$src" | wc -c)
copies=$(((min_bytes - head_bytes + body_bytes - 1) / body_bytes))
[ "$copies" -ge 1 ] || copies=1

tmp="$out.tmp.$$"
trap 'rm -f "$tmp"' EXIT
LC_ALL=C awk -v first="$first" -v end="$end" -v copies="$copies" -v top="$top_z" -v layers="$layers" '
function fmt(v,   s) {
  s = sprintf("%.3f", v)
  sub(/0+$/, "", s)
  sub(/\.$/, "", s)
  return s
}
# One body line, shifted by `dz` millimetres and `dl` layers.
function shifted(line, dz, dl,   n, f, i, out) {
  if (dz == 0) return line
  if (line ~ /^G[0-3] / && line ~ / Z/) {
    n = split(line, f, " ")
    out = f[1]
    for (i = 2; i <= n; i++) {
      if (substr(f[i], 1, 1) == "Z") f[i] = "Z" fmt(substr(f[i], 2) + dz)
      out = out " " f[i]
    }
    return out
  }
  if (line ~ /^;Z:/) return ";Z:" fmt(substr(line, 4) + dz)
  if (line ~ /^;[0-9.]+$/) return ";" fmt(substr(line, 2) + dz)
  if (line ~ /^SET_PRINT_STATS_INFO CURRENT_LAYER=/) return "SET_PRINT_STATS_INFO CURRENT_LAYER=" (substr(line, 36) + dl)
  return line
}
NR < first { print; next }
NR < end { body[++nbody] = $0; next }
NR == end {
  for (c = 0; c < copies; c++)
    for (i = 1; i <= nbody; i++) print shifted(body[i], c * top, c * layers)
}
{ print }
' "$src" >"$tmp"
mv "$tmp" "$out"
trap - EXIT
echo "make-large: $out: $(stat -c %s "$out") bytes, $copies x $layers layers of $(basename "$src")" >&2
