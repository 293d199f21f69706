#!/usr/bin/env bash
# `make bench`: per-stage times and peak memory of the pipeline, Meander side by side with
# OpenMesh and tinyobjloader, the end-to-end CLI run on a 10M-triangle binary PLY, curves
# of a chosen spacing, the mesh writers, wires and duotones, and this machine's floors,
# printed as markdown ready for docs/benchmarks.md. Builds nothing (`make bench` builds
# first); generated meshes go to $BUILD/bench/meshes.
#
# Environment: BUILD (build folder, default build), RUNS (runs per stage timing, default 5),
# CLI_RUNS (end-to-end runs, default 3), MEANDER_SHARED_MESHES (default ../shared/meshes).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${BUILD:-build}
runs=${RUNS:-5}
cli_runs=${CLI_RUNS:-3}
shared=${MEANDER_SHARED_MESHES:-../shared/meshes}
meander=$build/meander
scratch=$build/bench/meshes
for tool in "$meander" "$build/bench/meander_bench_stages" "$build/bench/meander_bench_peers" \
  "$build/bench/meander_bench_writers" "$build/bench/meander_bench_sculptures" "$build/bench/meander_bench_floors"; do
  [ -x "$tool" ] || { echo "run.sh: $tool is missing: run 'make bench' (or make build) first" >&2; exit 1; }
done
for mesh in bunny_closed.off stanford-bunny_original_holes.obj; do
  [ -f "$shared/$mesh" ] || { echo "run.sh: $shared/$mesh is missing (set MEANDER_SHARED_MESHES)" >&2; exit 1; }
done
mkdir -p "$scratch"

load() { cut -d' ' -f1 /proc/loadavg; }
# The middle value of the numbers on stdin (mean of the two middle ones for an even count).
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }

echo "## Machine"
echo
echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "- CPU: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores"
echo "- memory: $(awk '/MemTotal/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo)"
echo "- kernel: $(uname -sr)"
compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")
echo "- compiler: $("$compiler" --version | head -n 1)"
echo "- build type: $(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build/CMakeCache.txt")"
echo "- source: commit $(git rev-parse --short HEAD), plus $(git status --porcelain -- src include apps | wc -l)" \
  "uncommitted files or folders of src/ include/ apps/ that the build picked up"
echo "- load average at start: $(load)"
if awk -v l="$(load)" 'BEGIN { exit !(l > 0.5) }'; then
  echo "- **warning: load above 0.5, someone else is using the cores: re-run when the machine is quiet**"
fi

# Generated every time (a few seconds) so that they always match the current generator.
echo
echo "## Inputs"
echo
generate() { "$meander" generate "$@" 2>&1 | sed 's/^/- /'; }
generate sphere --faces 1000000 -o "$scratch/sphere_1m.ply"
generate sphere --faces 10000000 -o "$scratch/sphere_10m.ply"
generate sphere --faces 10000000 --shuffle 1 -o "$scratch/sphere_10m_shuffled.ply"
generate genus --genus 3 --faces 1000000 -o "$scratch/genus3_1m.ply"
generate sphere --faces 1000000 -o "$scratch/sphere_1m.obj"
generate sphere --faces 10000000 -o "$scratch/sphere_10m.obj"

echo
echo "## Stages (median of $runs runs in one process; peak RSS of that process)"
for mesh in "$shared/bunny_closed.off" "$scratch/sphere_1m.ply" "$scratch/sphere_10m.ply" "$scratch/genus3_1m.ply"; do
  echo
  "$build/bench/meander_bench_stages" "$mesh" --runs "$runs" | tee "$scratch/stages_$(basename "$mesh").txt"
done
triangles_10m=$(sed -n 's/^sphere_10m.ply: \([0-9]*\) input triangles.*/\1/p' "$scratch/stages_sphere_10m.ply.txt")

echo
echo "## Peers (Google Benchmark, median of 5 repetitions, same run)"
echo
echo '```'
"$build/bench/meander_bench_peers" "$shared/bunny_closed.off" "$shared/stanford-bunny_original_holes.obj" \
  "$scratch/sphere_1m.ply" "$scratch/sphere_10m.ply" "$scratch/sphere_1m.obj" "$scratch/sphere_10m.obj" \
  > "$scratch/peers.txt"
sed '/^$/,$d' "$scratch/peers.txt"
echo '```'
sed -n '/^$/,$p' "$scratch/peers.txt"
openmesh_ratio_10m=$(awk -F'|' '$2 ~ /^ sphere_10m.ply / { gsub(/ /, "", $8); print $8 }' "$scratch/peers.txt")

# GNU time (Debian package `time`) gives the CLI's own peak RSS; without it, only the time.
measure=()
[ -x /usr/bin/time ] && measure=(/usr/bin/time -f %M -o "$scratch/cli_rss_kb")
curve=$scratch/curve_10m.ply
# Runs `meander curve MESH -o $curve` $cli_runs times, with the environment variables given
# after MESH: the median wall clock in `seconds`, the largest peak RSS in peak_kb (KiB, 0
# without GNU time).
time_curve() {
  rm -f "$scratch/cli_seconds"
  peak_kb=0
  for ((i = 0; i < cli_runs; ++i)); do
    rm -f "$curve"
    start=$(date +%s.%N)
    "${measure[@]}" env "${@:2}" "$meander" curve "$1" -o "$curve"
    end=$(date +%s.%N)
    awk -v s="$start" -v e="$end" 'BEGIN { print e - s }' >> "$scratch/cli_seconds"
    [ ${#measure[@]} -eq 0 ] || peak_kb=$(( $(cat "$scratch/cli_rss_kb") > peak_kb ? $(cat "$scratch/cli_rss_kb") : peak_kb ))
  done
  seconds=$(median < "$scratch/cli_seconds")
  rm -f "$curve" "$scratch/cli_seconds"
}
# The same sphere with its vertices and faces shuffled, as some tools write meshes: the
# CLI puts it back in a locality order first (locality.h).
time_curve "$scratch/sphere_10m_shuffled.ply"
shuffled_seconds=$seconds
shuffled_bytes=$(awk -v k="$peak_kb" -v t="$triangles_10m" 'BEGIN { printf "%.0f", k * 1024 / t }')
# glibc puts every block it maps on transparent huge pages when the host asks it to: what
# a host where huge pages pay can choose (Meander advises only its largest arrays).
time_curve "$scratch/sphere_10m.ply" GLIBC_TUNABLES=glibc.malloc.hugetlb=1
tunable_seconds=$seconds
time_curve "$scratch/sphere_10m.ply"
cli_seconds=$seconds

echo
echo "## End to end: \`meander curve sphere_10m.ply -o curve.ply\` (median of $cli_runs)"
echo
echo "| target | measured | met |"
echo "|---|---:|---|"
verdict() { awk -v a="$1" -v b="$2" 'BEGIN { print (a <= b ? "yes" : "no") }'; }
printf '| 10M-triangle binary PLY to binary PLY curve <= 3 s | %.2f s | %s |\n' "$cli_seconds" "$(verdict "$cli_seconds" 3)"
printf '| the same, vertices and faces shuffled (generate --shuffle 1) | %.2f s, peak %s B per triangle | %s |\n' \
  "$shuffled_seconds" "$shuffled_bytes" "$(verdict "$shuffled_seconds" 3)"
printf '| 10M, not shuffled, under GLIBC_TUNABLES=glibc.malloc.hugetlb=1 | %.2f s | %s |\n' "$tunable_seconds" "$(verdict "$tunable_seconds" 3)"
if [ -n "$openmesh_ratio_10m" ] && [ "$openmesh_ratio_10m" != - ]; then
  echo "| read + connectivity >= 5x faster than OpenMesh (10M) | $openmesh_ratio_10m | $(verdict 5 "${openmesh_ratio_10m%x}") |"
else
  echo "| read + connectivity >= 5x faster than OpenMesh (10M) | did not run | - |"
fi
if [ "$peak_kb" -gt 0 ]; then
  bytes=$(awk -v k="$peak_kb" -v t="$triangles_10m" 'BEGIN { printf "%.0f", k * 1024 / t }')
  echo "| peak memory <= 150 bytes per input triangle (CLI, 10M) | $bytes B ($((peak_kb / 1024)) MiB) | $(verdict "$bytes" 150) |"
else
  echo "| peak memory <= 150 bytes per input triangle (CLI, 10M) | GNU time not installed | - |"
fi

# --spacing (docs/density.md): the curve at 1/50 of the bunny's diagonal and at 1/200 of a
# 1M-triangle sphere's, end to end (remesh, cycle, relaxation, write).
# Runs `meander curve MESH -o $curve --spacing (diagonal / FRACTION)` $cli_runs times: the
# median wall clock in `seconds`.
time_spacing() {
  local spacing
  spacing=$("$meander" info "$1" --json | python3 -c \
    "import json, math, sys; b = json.load(sys.stdin)['bounding_box']; print(math.dist(b['min'], b['max']) / $2)")
  rm -f "$scratch/cli_seconds"
  for ((i = 0; i < cli_runs; ++i)); do
    start=$(date +%s.%N)
    "$meander" curve "$1" -o "$curve" --spacing "$spacing"
    end=$(date +%s.%N)
    awk -v s="$start" -v e="$end" 'BEGIN { print e - s }' >> "$scratch/cli_seconds"
  done
  seconds=$(median < "$scratch/cli_seconds")
  rm -f "$curve" "$scratch/cli_seconds"
}
echo
echo "## Spacing: \`meander curve IN -o curve.ply --spacing D\` (median of $cli_runs)"
echo
echo "| target | measured | met |"
echo "|---|---:|---|"
time_spacing "$shared/bunny_closed.off" 50
printf '| bunny_closed.off at 1/50 of its diagonal <= 0.2 s | %.2f s | %s |\n' "$seconds" "$(verdict "$seconds" 0.2)"
time_spacing "$scratch/sphere_1m.ply" 200
printf '| 1M-triangle sphere at 1/200 of its diagonal <= 2 s | %.2f s | %s |\n' "$seconds" "$(verdict "$seconds" 2)"

# The studio's previews (docs/studio.md, Speed): studio/latency.mjs in Debian's Chromium,
# each mode's preview after a seed change, end to end in the page, median of 3.
echo
echo "## Studio previews: \`node studio/latency.mjs --previews\` (end to end in the page, median of 3)"
echo
if command -v node > /dev/null && [ -x "${CHROMIUM:-/usr/bin/chromium}" ]; then
  generate sphere --faces 50000 -o "$scratch/sphere_50k.ply"
  generate sphere --faces 200000 -o "$scratch/sphere_200k.ply"
  modes=(curve constant-ribbon constant-wire variable-ribbon:0 variable-wire:0 variable-wire:1 duotone:0)
  for faces in 50k 200k; do
    node studio/latency.mjs "$meander" "$scratch/sphere_$faces.ply" --previews "${modes[@]}" > "$scratch/latency_$faces.txt"
  done
  echo
  echo "| preview of | 50k faces (<= 300 ms) | met | 200k faces (<= 1 s) | met |"
  echo "|---|---:|---|---:|---|"
  # "MODE levels L preview: N triangles, end to end X ms (...)"
  ms() { sed -n "s/^$1 levels $2 preview: .* end to end \([0-9]*\) ms.*/\1/p" "$scratch/latency_$3.txt"; }
  for mode in "${modes[@]}"; do
    name=${mode%%:*}
    levels=${mode#*:}
    [ "$levels" = "$mode" ] && levels=1
    small=$(ms "$name" "$levels" 50k)
    large=$(ms "$name" "$levels" 200k)
    echo "| $name, levels $levels | $small ms | $(verdict "$small" 300) | $large ms | $(verdict "$large" 1000) |"
  done
  # With a spacing, counted on the remeshed faces: the bunny at the slider's finest
  # (1/300 of its diagonal, about 30k faces), the even surface kept as the seed changes.
  node studio/latency.mjs "$meander" "$shared/bunny_closed.off" --previews --spacing 0 "${modes[@]}" > "$scratch/latency_spacing.txt"
  echo
  echo "| preview of, bunny_closed.off with \`--spacing 0\` (<= 300 ms) | figure | met |"
  echo "|---|---:|---|"
  for mode in "${modes[@]}"; do
    name=${mode%%:*}
    levels=${mode#*:}
    [ "$levels" = "$mode" ] && levels=1
    spaced=$(ms "$name" "$levels" spacing)
    echo "| $name, levels $levels | $spaced ms | $(verdict "$spaced" 300) |"
  done
else
  echo "node or Chromium not installed: not measured (make test installs both)"
fi

# Plotter drawings (docs/drawing.md, Speed): hiding the parts behind the surface of a
# 1M-segment curve (a sphere of 84,000 faces, 4 samples a segment), the stage "draw" of
# `meander draw -v`, median of $cli_runs.
echo
echo "## Drawing: \`meander draw sphere_84k.ply -o drawing.svg\` (stage \"draw\", median of $cli_runs)"
echo
generate sphere --faces 84000 -o "$scratch/sphere_84k.ply" > /dev/null
for ((i = 0; i < cli_runs; ++i)); do
  "$meander" draw "$scratch/sphere_84k.ply" -o "$scratch/drawing.svg" -v 2>&1 | sed -n 's/^  draw *\([0-9.]*\) ms$/\1/p'
done > "$scratch/draw_ms"
draw_seconds=$(median < "$scratch/draw_ms" | awk '{ print $1 / 1000 }')
echo "| target | measured | met |"
echo "|---|---:|---|"
printf '| hidden-line drawing of a 1M-segment curve <= 2 s | %.2f s | %s |\n' "$draw_seconds" "$(verdict "$draw_seconds" 2)"
rm -f "$scratch/drawing.svg" "$scratch/draw_ms"

# A picture drawn with one line (docs/drawing.md, Speed): a 1000x1000 rendering of a
# pretzel on grey to an A4 single-line SVG at --spacing 0.37 mm (about 200,000 segments),
# the whole command from reading the PNG to the written SVG, median of $cli_runs.
echo
echo "## Line picture: \`meander image scene_1mp.png -o image.svg --spacing 0.37\` (whole command, median of $cli_runs)"
echo
generate pretzel --faces 20000 -o "$scratch/pretzel_20k.ply" > /dev/null
"$meander" render "$scratch/pretzel_20k.ply" -o "$scratch/scene_1mp.png" --size 1000x1000 --view front --background '#707080' > /dev/null 2>&1
for ((i = 0; i < cli_runs; ++i)); do
  start=$(date +%s%N)
  "$meander" image "$scratch/scene_1mp.png" -o "$scratch/image.svg" --spacing 0.37 2> /dev/null
  echo $((($(date +%s%N) - start) / 1000000))
done > "$scratch/image_ms"
image_seconds=$(median < "$scratch/image_ms" | awk '{ print $1 / 1000 }')
segments=$(grep -o ' L' "$scratch/image.svg" | wc -l)
echo "| target | measured | met |"
echo "|---|---:|---|"
printf '| a 1-megapixel picture to a single-line SVG (%d segments) <= 1 s | %.2f s | %s |\n' "$segments" "$image_seconds" "$(verdict "$image_seconds" 1)"
rm -f "$scratch/image.svg" "$scratch/image_ms"

# The Python package's overhead over the C++ call (docs/python.md): the same curve, median
# of $runs each, in the same run.
echo
echo "## Python: \`meander.curve(mesh)\` against the C++ call (median of $runs)"
echo
echo "| call | Python | C++ | overhead (target <= 5%) |"
echo "|---|---:|---:|---:|"
PYTHONPATH=$build/python /usr/bin/python3 bench/python_overhead.py "$build" "$scratch/sphere_1m.ply" "$runs"

# Google Benchmark's console table (medians), without the context lines it prints first.
gbench_table() { echo '```'; "$@" | sed -n '/^---/,$p'; echo '```'; }

echo
echo "## Mesh writers (Google Benchmark, median of 9 repetitions)"
echo
gbench_table "$build/bench/meander_bench_writers" --benchmark_counters_tabular=true | tee "$scratch/writers.txt"
echo
echo "| target | measured | met |"
echo "|---|---:|---|"
for format in stl ply; do
  rate=$(sed -n "s/^write_binary\.${format}\/.*_median .* \([0-9.]*\)M\/s .*/\1/p" "$scratch/writers.txt")
  printf '| binary %s writer >= 20 M triangles/s (3M triangles) | %s M/s | %s |\n' "${format^^}" "${rate:--}" \
    "$( [ -n "$rate" ] && verdict 20 "$rate" || echo -)"
done

echo
echo "## Wires and duotone of $(basename "$shared/bunny_closed.off") (Google Benchmark, median of 5, variable wire 3)"
echo
gbench_table "$build/bench/meander_bench_sculptures" --benchmark_counters_tabular=true "$shared/bunny_closed.off"

# What any program of the CLI's footprint and output pays here, whatever its algorithms:
# 1.3 GiB of fresh memory (its peak) and a file the size of the 10M curve (2.23 GiB).
echo
echo "## Floors of this machine (3 runs of meander_bench_floors, each a fresh process)"
echo
echo "| run | what | first time | again |"
echo "|---|---|---:|---:|"
for ((i = 1; i <= 3; ++i)); do
  "$build/bench/meander_bench_floors" --memory-gb 1.3 --write "$scratch/floor.bin" --write-gb 2.23 | tail -n +3 | sed "s/^/| $i /"
done
echo
echo "load average at end: $(load)"
