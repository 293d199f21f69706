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
# A portrait-like scene rendered by Meander (the face mask of ../shared/meshes), drawn
# with one closed line, and its duotone (their SVGs, 3.5 MB each, are not kept).
meshes=${MEANDER_SHARED_MESHES:-../shared/meshes}
"$meander" render "$meshes/face.obj" -o docs/images/image_face_scene.png --size 450x600 --view front --fit --background '#3a3a44'
"$meander" image docs/images/image_face_scene.png -o "$work/face.svg" --paper A5 --margin 8mm --spacing 0.35mm \
  --max-spacing 2.5mm --gamma 0.7 --seed 2 --duotone "$work/face_duotone.svg"
rsvg-convert -w 700 -b white "$work/face.svg" -o docs/images/image_face.png
rsvg-convert -w 350 -b white "$work/face_duotone.svg" -o docs/images/image_face_duotone.png
