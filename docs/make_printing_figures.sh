#!/bin/sh
# The figures of docs/printing.md, made by `meander wire --png`, `duotone --png` and
# `render` (run by `make gallery`). MEANDER is the CLI, MESHES the real meshes
# (../shared/meshes).
set -eu
cd "$(dirname "$0")"
MEANDER=${MEANDER:-../build/meander}
MESHES=${MESHES:-../../shared/meshes}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

"$MEANDER" generate pretzel -o "$OUT/pretzel.ply"
# A 100 mm pretzel, its passes 6 mm apart, bridged so that no stretch of 20 mm goes free.
"$MEANDER" wire "$OUT/pretzel.ply" -o "$OUT/bridged.stl" --model-size 100mm --spacing 6mm --bridges 20mm \
  --png images/printing_bridges_pretzel.png --size 900x600 --view 30,50 --fit

# A two-colour print of Spot at 100 mm, its passes 4 mm apart, with a 1.5 mm wall: the
# painted surface, and the first colour's solid alone.
"$MEANDER" duotone "$MESHES/spot_triangulated.obj" --model-size 100mm --spacing 4mm --shell 1.5mm \
  -o "$OUT/spot.3mf" --parts "$OUT/spot_1.ply,$OUT/spot_2.ply" \
  --png images/printing_shell_spot.png --size 900x600 --view -60,15 --fit
"$MEANDER" render "$OUT/spot_1.ply" -o images/printing_shell_spot_piece.png --size 900x600 --view -60,15 --fit

# The bunny at 100 mm with the same wall: its ears are too thin and fold too sharply for a
# wall that follows the quads, so the shell is sampled; the first colour's solid alone.
"$MEANDER" duotone "$MESHES/bunny_closed.off" --model-size 100mm --spacing 4mm --shell 1.5mm \
  -o "$OUT/bunny.3mf" --parts "$OUT/bunny_1.ply,$OUT/bunny_2.ply" \
  --png images/printing_shell_bunny.png --size 900x600 --fit
"$MEANDER" render "$OUT/bunny_1.ply" -o images/printing_shell_bunny_piece.png --size 900x600 --fit
# The same with a 0.3 mm gap, to print the pieces apart (minutes: the gap is sampled finely).
"$MEANDER" duotone "$MESHES/bunny_closed.off" --model-size 100mm --spacing 4mm --shell 1.5mm --clearance 0.3mm \
  -o "$OUT/bunny_apart.3mf" --parts "$OUT/bunny_apart_1.stl,$OUT/bunny_apart_2.stl"
"$MEANDER" render "$OUT/bunny_apart_1.stl" -o images/printing_apart_bunny_piece.png --size 900x600 --fit
