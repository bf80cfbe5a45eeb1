#!/bin/sh
# Writes an ASCII STL of a star-shaped prism to standard output: a small,
# closed, printable part for the recipes in this folder (no download needed).
#   make-star-stl.sh [POINTS [OUTER_MM [INNER_MM [HEIGHT_MM]]]]   (5 12 6 6)
# The outline alternates the outer and inner radius; top and bottom are fans
# from the centre (the outline is star-shaped about it), the sides two
# triangles per edge, every facet wound counter-clockwise seen from outside.
points=${1:-5} outer=${2:-12} inner=${3:-6} height=${4:-6}
awk -v n="$points" -v ro="$outer" -v ri="$inner" -v h="$height" 'BEGIN {
  pi = atan2(0, -1)
  m = 2 * n
  for (i = 0; i < m; i++) {
    r = (i % 2 == 0) ? ro : ri
    a = pi / 2 + i * pi / n
    x[i] = r * cos(a); y[i] = r * sin(a)
  }
  print "solid star"
  for (i = 0; i < m; i++) {
    j = (i + 1) % m
    facet(0, 0, -1, 0, 0, 0, x[j], y[j], 0, x[i], y[i], 0)         # bottom, seen from below
    facet(0, 0, 1, 0, 0, h, x[i], y[i], h, x[j], y[j], h)          # top
    nx = y[j] - y[i]; ny = x[i] - x[j]; l = sqrt(nx * nx + ny * ny)
    facet(nx / l, ny / l, 0, x[i], y[i], 0, x[j], y[j], 0, x[j], y[j], h)
    facet(nx / l, ny / l, 0, x[i], y[i], 0, x[j], y[j], h, x[i], y[i], h)
  }
  print "endsolid star"
}
function facet(nx, ny, nz, ax, ay, az, bx, by, bz, cx, cy, cz) {
  printf "  facet normal %.6f %.6f %.6f\n    outer loop\n", nx, ny, nz
  printf "      vertex %.6f %.6f %.6f\n      vertex %.6f %.6f %.6f\n      vertex %.6f %.6f %.6f\n", ax, ay, az, bx, by, bz, cx, cy, cz
  printf "    endloop\n  endfacet\n"
}'
