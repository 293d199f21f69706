#!/usr/bin/env bash
# Regenerates the figures of docs/density.md with Meander itself: a scan (the kitten of
# ../shared/meshes) at its own density and at three spacings, at 1/60 also unrelaxed and
# at three branches, the evenness table, and a printable 100 mm wire of the pretzel.
set -euo pipefail
cd "$(dirname "$0")/.."
meander=${MEANDER:-build/meander}
meshes=${MESHES:-../shared/meshes}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
kitten="$meshes/kitten.off"
picture=(--size 640x640 --view front --fit --occluder-style shaded)
"$meander" curve "$kitten" -o "$scratch/own.ply" --png docs/images/density_kitten_own.png "${picture[@]}"
"$meander" info "$kitten" --curve "$scratch/own.ply" | grep -E "gap|coverage"
# The kitten's bounding-box diagonal is 2.66 of its units: 1/30, 1/60, 1/120 of it.
for fraction in 30 60 120; do
  spacing=$(python3 -c "print(round(2.66 / $fraction, 4))")
  "$meander" curve "$kitten" -o "$scratch/$fraction.ply" --spacing "$spacing" \
    --png "docs/images/density_kitten_$fraction.png" "${picture[@]}"
  echo "spacing $spacing (1/$fraction of the diagonal):"
  "$meander" info "$kitten" --curve "$scratch/$fraction.ply" | grep -E "gap|coverage"
done
# The curve at 1/60 as made on the even mesh (--relax 0), before the relaxation evens it.
"$meander" curve "$kitten" -o "$scratch/raw.ply" --spacing 0.0443 --relax 0 \
  --png docs/images/density_kitten_60_unrelaxed.png "${picture[@]}"
echo "spacing 0.0443 without relaxation:"
"$meander" info "$kitten" --curve "$scratch/raw.ply" | grep -E "gap|coverage"
# Branches: the same spacing with the waviness at 0, 0.5 and 1 (-v prints the leaves).
for branches in 0 0.5 1; do
  "$meander" curve "$kitten" -o "$scratch/b.ply" --spacing 0.0443 --branches "$branches" -v \
    --png "docs/images/density_kitten_branches_$branches.png" "${picture[@]}" 2>&1 | grep "leaves" |
    sed "s/^/branches $branches: /"
done
# A printable wire 100 mm long of the generated pretzel, with its report.
"$meander" generate pretzel --faces 6400 -o "$scratch/pretzel.obj" > /dev/null
"$meander" wire "$scratch/pretzel.obj" -o "$scratch/pretzel_wire.stl" --model-size 100mm --spacing 3mm \
  --png docs/images/density_pretzel_wire_100mm.png --size 640x480
