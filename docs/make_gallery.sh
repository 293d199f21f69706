#!/usr/bin/env bash
# Regenerates the pictures of docs/gallery.md (and the README) with Meander itself:
# `meander curve ... --png` draws each curve with its surface as occluder (the parts
# behind the surface hidden, the surface itself faint), `meander render` draws a curve
# file over any occluder.
set -euo pipefail
cd "$(dirname "$0")/.."
meander=${MEANDER:-build/meander}
meshes=${MEANDER_SHARED_MESHES:-../shared/meshes}
out=docs/images
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# The same sphere with each spanning-tree style (the paper's Figure 1 shows variants),
# drawn as flat ribbons: the pattern is what differs, and flat colours keep the files small.
for tree in random uniform bfs dfs; do
  "$meander" curve "$meshes/sphere.obj" -o "$scratch/sphere_$tree.obj" --tree "$tree" --seed 7 \
    --png "$out/sphere_$tree.png" --size 240x240 --view front --fit --occluder-style faint --curve-style ribbon
done
# Higher genus: a generated genus-3 surface and the genus-4 Fertility statue.
"$meander" generate genus --genus 3 --faces 2000 -o "$scratch/genus3.obj"
"$meander" curve "$scratch/genus3.obj" -o "$scratch/genus3_curve.obj" --tree uniform --seed 3 \
  --png "$out/genus3.png" --size 400x300 --view 15,25 --fit --occluder-style faint
"$meander" curve "$meshes/fertility.off" -o "$scratch/fertility_curve.obj" --tree uniform --seed 3 \
  --png "$out/fertility.png" --size 400x300 --view front --fit --occluder-style faint
# The paper's Figure 2: the Stanford bunny's curve (70k input triangles, 836k points),
# its back parts hidden by the surface, which is not drawn. So dense a curve reads only
# as thin lines of one width: flat ribbons of 1.1 pixels on a picture large enough.
"$meander" curve "$meshes/bunny_closed.off" -o "$scratch/bunny_curve.ply" --tree uniform --seed 3
"$meander" render "$scratch/bunny_curve.ply" --occluder "$meshes/bunny_closed.off" -o "$out/bunny.png" \
  --size 900x900 --view front --fit --curve-style ribbon --curve-width 1.1 --samples 2
