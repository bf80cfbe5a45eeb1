#!/usr/bin/env bash
# Test pictures for the lithophane benchmark (bench/litho-vs-cura.sh), made
# with ImageMagick so they are the same on every machine. Each stresses one
# thing a portrait has:
#   light.png    large light areas: a pale sky over a pale field, a thin dark
#                horizon and a few small dark marks (thin plate: walls dominate)
#   dark.png     large dark areas: a dark gradient with one light disc
#                (thick plate: wide beads, several passes)
#   detail.png   fine detail: stripes whose period shrinks from 8 pixels to
#                three across the picture, over a grey ramp (short passes, many
#                turns, the pass count changing often)
#   portrait.png a drawn face: light background, dark hair, mid-tone skin,
#                dark eyes and mouth, blurred as a photograph is
#
#   bench/litho-pictures.sh DIR
set -euo pipefail
dir=${1:?give the directory}
mkdir -p "$dir"
cd "$dir"
convert -size 200x150 gradient:'gray80-white' \
  -fill gray15 -draw 'rectangle 0,98 199,100' -draw 'circle 150,40 154,40' -draw 'circle 40,120 43,120' \
  -fill gray55 -draw 'rectangle 20,60 24,97' light.png
convert -size 200x150 gradient:'black-gray35' -fill gray95 -draw 'circle 120,70 120,95' dark.png
convert -size 200x150 xc: -fx 'j/h*0.6 + 0.4*(sin(2*pi*(i/8 + 0.104*i*i/w)) > 0)' -colorspace Gray detail.png
convert -size 150x200 xc:gray92 -fill gray25 -draw 'ellipse 75,95 52,70 0,360' \
  -fill gray60 -draw 'ellipse 75,110 40,55 0,360' -fill gray10 -draw 'ellipse 58,100 7,4 0,360' \
  -draw 'ellipse 92,100 7,4 0,360' -fill gray35 -draw 'ellipse 75,140 14,4 0,360' -blur 0x1.5 portrait.png
