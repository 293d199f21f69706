#!/bin/sh
# The duotone figures of docs/duotone.md, made by `meander duotone --png` (run by
# `make gallery`). MEANDER is the CLI, MESHES the real meshes (../shared/meshes).
set -eu
cd "$(dirname "$0")"
MEANDER=${MEANDER:-../build/meander}
MESHES=${MESHES:-../../shared/meshes}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

# Figure 3: the bunny and the Fertility statue (genus 4), smooth (one subdivision level).
"$MEANDER" duotone "$MESHES/bunny_closed.off" -o "$OUT/bunny.glb" --quad dual-simplest --tree uniform --seed 2 \
  --png images/duotone_bunny.png --size 900x900 --view front --fit
"$MEANDER" duotone "$MESHES/fertility.off" -o "$OUT/fertility.glb" --tree uniform --seed 2 --subdivide 1 \
  --png images/duotone_fertility.png --size 700x700 --view front --fit
# Figure 22: a genus-3 surface of 82 hexagons and heptagons, as a subdivision surface,
# then the same at a higher frequency (its Catmull-Clark quads used as the input).
"$MEANDER" duotone "$MESHES/genus3hexa1.obj" -o "$OUT/genus3.obj" --subdivide 2 --texture-size 512 \
  --png images/duotone_genus3.png --size 600x450 --view 15,35 --fit
"$MEANDER" duotone "$MESHES/genus3hexa1.obj" -o "$OUT/genus3_quads.obj" --texture-size 64
"$MEANDER" duotone "$OUT/genus3_quads.obj" -o "$OUT/genus3_dense.obj" --subdivide 2 --tree uniform \
  --png images/duotone_genus3_dense.png --size 600x450 --view 15,35 --fit
# Figure 23: a badly triangulated mesh: a CAD export (STL) full of long thin triangles.
"$MEANDER" duotone "$MESHES/conrod.stl" -o "$OUT/conrod.glb" --quad dual-simplest \
  --png images/duotone_conrod.png --size 700x500 --view 30,40 --fit
# Figure 21: each tile style on the same smooth pretzel, tiles large enough to show them.
"$MEANDER" generate pretzel --faces 200 -o "$OUT/pretzel.obj"
for style in truchet outline triangles stripes dots; do
  "$MEANDER" duotone "$OUT/pretzel.obj" -o "$OUT/pretzel_$style.glb" --tiles "$style" --seed 4 --subdivide 2 \
    --colors navy,cream --png "images/duotone_tiles_$style.png" --size 480x360 --view 10,40 --fit
done
