#!/usr/bin/env bash
# Regenerates the pictures of docs/gallery.md (and the README) with Meander itself:
# `meander curve ... --png` draws each curve on the surface it covers.
set -euo pipefail
cd "$(dirname "$0")/.."
meander=${MEANDER:-build/meander}
meshes=${MEANDER_SHARED_MESHES:-../shared/meshes}
out=docs/images
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# The same sphere with each spanning-tree style (the paper's Figure 1 shows variants).
for tree in random uniform bfs dfs; do
  "$meander" curve "$meshes/sphere.obj" -o "$scratch/sphere_$tree.obj" --tree "$tree" --seed 7 \
    --png "$out/sphere_$tree.png" --size 320x240 --view front
done
# Higher genus: a generated genus-3 surface and the genus-4 Fertility statue.
"$meander" generate genus --genus 3 --faces 2000 -o "$scratch/genus3.obj"
"$meander" curve "$scratch/genus3.obj" -o "$scratch/genus3_curve.obj" --tree uniform --seed 3 \
  --png "$out/genus3.png" --size 400x300 --view 15,25
"$meander" curve "$meshes/fertility.off" -o "$scratch/fertility_curve.obj" --tree uniform --seed 3 \
  --png "$out/fertility.png" --size 400x300 --view front
