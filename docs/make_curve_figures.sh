#!/usr/bin/env bash
# Regenerates the SVG figures of docs/curve.md with Meander itself:
# the same generated open grid with each spanning-tree style.
set -euo pipefail
cd "$(dirname "$0")/.."
meander=${MEANDER:-build/meander}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
"$meander" generate grid --faces 450 -o "$scratch/grid.obj"
for tree in random uniform bfs dfs; do
  "$meander" curve "$scratch/grid.obj" -o "docs/images/tree_$tree.svg" --tree "$tree" --seed 7 --samples 2
done
