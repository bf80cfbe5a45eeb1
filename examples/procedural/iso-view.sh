#!/usr/bin/env bash
# An isometric picture (SVG) of a G-code part's extruded path, to see what a
# formula made of it: gc-layers --svg draws layers from above, this the whole.
#
#   examples/procedural/iso-view.sh PART.gcode > PART-iso.svg
#   examples/procedural/iso-view.sh --shade PART.gcode > PART-iso.svg
#
# Absolute XYZ (G90, as gc-shape and gc-deform write); extruding G1 moves from
# the first ;LAYER: on are drawn (not the start code's purge, not travel); points closer than 0.4 mm on the picture are merged.
# --shade: each move darker the more filament it lays a mm (a texture that
# gc-litho --texture paints by head speed at a constant extruder rate shows
# as the thicker, slower beads), in four shades from 0.6 of the file's most
# filament a mm (and below) to the most; E absolute or relative (M82/M83, G92).
# The far half of the part (beyond its box's centre, seen from the viewer)
# is drawn first, thin and grey, so that the near half's shades stand out.
set -euo pipefail
shade=0
if [ "${1:-}" = --shade ]; then
  shade=1
  shift
  [ $# -eq 1 ] || { echo "usage: iso-view.sh --shade PART.gcode (a file: it is read twice)" >&2; exit 2; }
  set -- "$1" "$1"
fi
awk -v shade="$shade" '
function flush() { if (n > 1) { paths[++np] = d; tone[np] = level } n = 0; d = "" }
function point(u, v) {
  if (n > 0 && (u - lu) ^ 2 + (v - lv) ^ 2 < (level < 0 ? 1 : 0.16)) return
  d = d sprintf("%s%.1f %.1f", n == 0 ? "M" : " L", u, -v); n++; lu = u; lv = v
  if (u < minu) minu = u; if (u > maxu) maxu = u; if (-v < minv) minv = -v; if (-v > maxv) maxv = -v
}
# A move: sets x y z, and de (the filament it lays, 0 if none).
function move(   i, l, v, e) {
  e = ""
  for (i = 2; i <= NF; i++) {
    l = substr($i, 1, 1); v = substr($i, 2) + 0
    if (l == "X") x = v; else if (l == "Y") y = v; else if (l == "Z") z = v; else if (l == "E") e = v
  }
  de = 0
  if (e != "") { de = relative ? e : e - ee; ee = relative ? ee : e }
}
BEGIN { minu = minv = near = 1e9; maxu = maxv = far = -1e9; c = 0.8660254; s = 0.5; level = 0; pass = shade ? 1 : 2 }
FNR == 1 && NR > 1 { pass = 2; x = y = z = ee = 0; relative = 0; layers = 0; have = 0 }
/^;LAYER:/ { layers = 1 }
{ sub(/;.*/, "") }
$1 == "M83" { relative = 1 }
$1 == "M82" { relative = 0 }
$1 == "G92" { for (i = 2; i <= NF; i++) if (substr($i, 1, 1) == "E") ee = substr($i, 2) + 0 }
$1 == "G0" || $1 == "G1" {
  px = x; py = y
  move()
  len = sqrt((x - px) ^ 2 + (y - py) ^ 2)
  if (pass == 1) {
    if ($1 == "G1" && de > 0 && layers) {
      if (len >= 0.1 && de / len > most) most = de / len
      if (x + y < near) near = x + y; if (x + y > far) far = x + y
    }
    next
  }
  u = (x - y) * c; w = z + (x + y) * s * 0.5
  if ($1 == "G1" && de > 0 && have && layers) {
    if (shade && len > 0) {
      t = int((de / len / most - 0.6) / 0.4 * 4); t = t < 0 ? 0 : (t > 3 ? 3 : t)
      if (x + y + px + py > near + far) t = -1  # the far half
      if (t != level) { flush(); level = t }
    }
    if (n == 0) point(pu, pw)
    point(u, w)
  } else flush()
  pu = u; pw = w; have = 1
}
END {
  flush(); m = 4
  split("#e8a89f #d46a5c #b03a2e #6e1f17", colour)
  printf "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"%.1f %.1f %.1f %.1f\" width=\"%d\" height=\"%d\">\n",
    minu - m, minv - m, maxu - minu + 2 * m, maxv - minv + 2 * m, 4 * (maxu - minu + 2 * m), 4 * (maxv - minv + 2 * m)
  printf "<rect x=\"%.1f\" y=\"%.1f\" width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n", minu - m, minv - m
  if (!shade) {
    print "<g fill=\"none\" stroke=\"#c0392b\" stroke-width=\"0.12\" stroke-opacity=\"0.7\">"
    for (i = 1; i <= np; i++) print "<path d=\"" paths[i] "\"/>"
    print "</g>"
  } else {
    print "<g fill=\"none\" stroke=\"#d0d0d0\" stroke-width=\"0.12\">"
    for (i = 1; i <= np; i++) if (tone[i] < 0) print "<path d=\"" paths[i] "\"/>"
    print "</g>"
    for (t = 0; t < 4; t++) {
      printf "<g fill=\"none\" stroke=\"%s\" stroke-width=\"0.25\">\n", colour[t + 1]
      for (i = 1; i <= np; i++) if (tone[i] == t) print "<path d=\"" paths[i] "\"/>"
      print "</g>"
    }
  }
  print "</svg>"
}' "$@"
