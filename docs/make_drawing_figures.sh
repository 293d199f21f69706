#!/usr/bin/env bash
# The figures of docs/drawing.md, made by Meander (`meander draw`) and rasterised by
# Debian's rsvg-convert (librsvg2-bin), an independent renderer.
# Usage: MEANDER=build/meander docs/make_drawing_figures.sh
set -euo pipefail
cd "$(dirname "$0")/.."
meander=${MEANDER:-build/meander}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$meander" generate pretzel --faces 6400 -o "$work/pretzel.obj"
"$meander" draw "$work/pretzel.obj" -o docs/images/drawing_pretzel.svg --paper A5 --landscape --seed 7 \
  --png docs/images/drawing_pretzel_preview.png --size 800x566
rsvg-convert -w 800 -b white docs/images/drawing_pretzel.svg -o docs/images/drawing_pretzel.png
