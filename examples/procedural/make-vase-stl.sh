#!/bin/sh
# Writes an ASCII STL of a vase to standard output: a belly and six flutes
# that turn as they rise, a floor, an open top; a model for gc-shape vase
# --mesh (no download needed).
#   make-vase-stl.sh [HEIGHT_MM [AROUND [RINGS]]]   (40 120 80)
# Radius at angle a and height z: 13 + 5 sin(pi z / H) + 1.2 sin(6 a + 2 z / H).
# The wall is two triangles per facet of a ring, the floor a fan from the
# centre; every facet wound counter-clockwise seen from outside.
height=${1:-40} around=${2:-120} rings=${3:-80}
awk -v h="$height" -v n="$around" -v m="$rings" 'BEGIN {
  pi = atan2(0, -1)
  for (j = 0; j <= m; j++) {
    z[j] = h * j / m
    for (i = 0; i < n; i++) {
      a = 2 * pi * i / n
      r = 13 + 5 * sin(pi * z[j] / h) + 1.2 * sin(6 * a + 2 * z[j] / h)
      x[j, i] = r * cos(a); y[j, i] = r * sin(a)
    }
  }
  print "solid vase"
  for (i = 0; i < n; i++) {
    k = (i + 1) % n
    facet(0, 0, 0, x[0, k], y[0, k], 0, x[0, i], y[0, i], 0)    # floor, seen from below
    for (j = 0; j < m; j++) {
      facet(x[j, i], y[j, i], z[j], x[j, k], y[j, k], z[j], x[j + 1, k], y[j + 1, k], z[j + 1])
      facet(x[j, i], y[j, i], z[j], x[j + 1, k], y[j + 1, k], z[j + 1], x[j + 1, i], y[j + 1, i], z[j + 1])
    }
  }
  print "endsolid vase"
}
# The normal is left 0 0 0: readers (gc-shape, CuraEngine) take the winding.
function facet(ax, ay, az, bx, by, bz, cx, cy, cz) {
  printf "  facet normal 0 0 0\n    outer loop\n"
  printf "      vertex %.5f %.5f %.5f\n      vertex %.5f %.5f %.5f\n      vertex %.5f %.5f %.5f\n", ax, ay, az, bx, by, bz, cx, cy, cz
  printf "    endloop\n  endfacet\n"
}'
