#!/bin/sh
# The wire figures of docs/wires.md, made by `meander wire --png` (run by `make gallery`).
# MEANDER is the CLI, MESHES the real meshes (../shared/meshes).
set -eu
cd "$(dirname "$0")"
MEANDER=${MEANDER:-../build/meander}
MESHES=${MESHES:-../../shared/meshes}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

# Figures 8 and 12 of the paper: constant vs variable, wire vs ribbon, on one sphere.
for method in constant variable; do
  for shape in wire ribbon; do
    "$MEANDER" wire "$MESHES/sphere.obj" -o "$OUT/sphere.stl" --method "$method" --shape "$shape" --seed 3 \
      --png "images/wire_sphere_${method}_${shape}.png" --size 300x300 --view 20,20
  done
done
# Figure 2: dense ribbons (s = t = 0.8) that almost cover the surface.
"$MEANDER" wire "$MESHES/spot_triangulated.obj" -o "$OUT/spot.ply" --method variable --shape ribbon --s 0.8 --t 0.8 \
  --png images/wire_spot_dense_ribbon.png --size 440x440 --view 60,20
# Figure 14: constant-diameter wires on a quad mesh used as it is.
"$MEANDER" wire "$MESHES/spot_quadrangulated.obj" --quad none --radius 0.0035 -o "$OUT/spot_quads.stl" \
  --png images/wire_spot_quads.png --size 440x440 --view 60,20
# A coarse CAD-like mesh whose rectangles make slivers: the variable wire on the shaped tree.
"$MEANDER" wire "$MESHES/beveledcube.obj" -o "$OUT/cube.stl" --method variable \
  --png images/wire_beveledcube_variable.png --size 300x300 --view 30,25
# Warped hexagons of a genus-3 mesh, split into stars of triangles before the slabs.
"$MEANDER" wire "$MESHES/genus3hexa1.obj" -o "$OUT/genus3.stl" --method variable \
  --png images/wire_genus3hexa1_variable.png --size 400x320 --view 20,30
# A scan with strips of needles, a folded sliver and sharp creases (docs/wires.md, items
# 1 and 6), at level 1 for the picture's sake (seed 2: clear there; docs/wires.md).
"$MEANDER" wire "$MESHES/camelhead.off" -o "$OUT/camel.stl" --method variable --levels 1 --seed 2 \
  --png images/wire_camelhead_variable.png --size 720x440 --view 270,15 --fit
