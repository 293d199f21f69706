#!/bin/sh
# The figures of docs/printing.md, made by `meander wire --png` (run by `make gallery`).
# MEANDER is the CLI.
set -eu
cd "$(dirname "$0")"
MEANDER=${MEANDER:-../build/meander}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

"$MEANDER" generate pretzel -o "$OUT/pretzel.ply"
# A 100 mm pretzel, its passes 6 mm apart, bridged so that no stretch of 20 mm goes free.
"$MEANDER" wire "$OUT/pretzel.ply" -o "$OUT/bridged.stl" --model-size 100mm --spacing 6mm --bridges 20mm \
  --png images/printing_bridges_pretzel.png --size 900x600 --view 30,50 --fit
