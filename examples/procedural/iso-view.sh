#!/usr/bin/env bash
# An isometric picture (SVG) of a G-code part's extruded path, to see what a
# formula made of it: gc-layers --svg draws layers from above, this the whole.
#
#   examples/procedural/iso-view.sh PART.gcode > PART-iso.svg
#
# Absolute XYZ (G90, as gc-shape and gc-deform write); extruding G1 moves from
# the first ;LAYER: on are drawn (not the start code's purge, not travel); points closer than 0.4 mm on the picture are merged.
set -euo pipefail
awk '
function flush() { if (n > 1) paths[++np] = d; n = 0; d = "" }
function point(u, v) {
  if (n > 0 && (u - lu) ^ 2 + (v - lv) ^ 2 < 0.16) return
  d = d sprintf("%s%.1f %.1f", n == 0 ? "M" : " L", u, -v); n++; lu = u; lv = v
  if (u < minu) minu = u; if (u > maxu) maxu = u; if (-v < minv) minv = -v; if (-v > maxv) maxv = -v
}
BEGIN { minu = minv = 1e9; maxu = maxv = -1e9; c = 0.8660254; s = 0.5 }
/^;LAYER:/ { layers = 1 }
{ sub(/;.*/, "") }
$1 == "G0" || $1 == "G1" {
  e = 0
  for (i = 2; i <= NF; i++) {
    l = substr($i, 1, 1); v = substr($i, 2) + 0
    if (l == "X") x = v; else if (l == "Y") y = v; else if (l == "Z") z = v; else if (l == "E") e = 1
  }
  u = (x - y) * c; w = z + (x + y) * s * 0.5
  if ($1 == "G1" && e && have && layers) { if (n == 0) point(pu, pw); point(u, w) } else flush()
  pu = u; pw = w; have = 1
}
END {
  flush(); m = 4
  printf "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"%.1f %.1f %.1f %.1f\" width=\"%d\" height=\"%d\">\n",
    minu - m, minv - m, maxu - minu + 2 * m, maxv - minv + 2 * m, 4 * (maxu - minu + 2 * m), 4 * (maxv - minv + 2 * m)
  printf "<rect x=\"%.1f\" y=\"%.1f\" width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n", minu - m, minv - m
  print "<g fill=\"none\" stroke=\"#c0392b\" stroke-width=\"0.12\" stroke-opacity=\"0.7\">"
  for (i = 1; i <= np; i++) print "<path d=\"" paths[i] "\"/>"
  print "</g>\n</svg>"
}' "$@"
