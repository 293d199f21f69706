#!/usr/bin/env bash
# Runs every fuzz target of a MEANDER_BUILD_FUZZ build for SECONDS each, one after the
# other (each on one core), and stops at the first finding, leaving its input in
# BUILD/fuzz-runs/TARGET/ as libFuzzer names it (crash-*, leak-*, timeout-*, oom-*).
# Usage: fuzz/run.sh BUILD SECONDS [TARGET...]
# FUZZ_TIMEOUT (default 10): the seconds of wall clock one input may take; raise it for
# runs niced beside other work, where a starved fuzzer waits for a core far longer.
# Seeds: fuzz/seeds/TARGET/ (hand-made), the files of tests/corpus/ and the small meshes
# of ../shared/meshes with the target's extension (linked in place, not copied), and the
# regressions of tests/regressions/TARGET/. New inputs grow BUILD/fuzz-runs/TARGET/corpus/,
# which a later run starts from.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=$(cd "$1" && pwd)
seconds=$2
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_read_obj fuzz_read_ply fuzz_read_stl fuzz_read_off fuzz_read_gltf fuzz_repair fuzz_curve fuzz_studio_request fuzz_studio_upload fuzz_studio_http)
meshes=${MEANDER_SHARED_MESHES:-$root/../shared/meshes}

# Links the files of folder $1 with one of the extensions $3... and at most 64 KiB into $2.
link_files() {
  local from=$1 to=$2 file
  shift 2
  [ -d "$from" ] || return 0
  for file in "$from"/*; do
    [ -f "$file" ] && [ "$(stat -c %s "$file")" -le 65536 ] || continue
    for extension in "$@"; do
      case "${file,,}" in *."$extension") ln -sf "$file" "$to/$(basename "$(dirname "$file")")_$(basename "$file")" ;; esac
    done
  done
}

for target in "${targets[@]}"; do
  work=$build/fuzz-runs/$target
  mkdir -p "$work/corpus" "$work/seeds"
  find "$work/seeds" -type l -delete
  case $target in
    fuzz_read_gltf) extensions=(gltf glb) ;;
    fuzz_read_*) extensions=("${target#fuzz_read_}") ;;
    *) extensions=() ;;
  esac
  if [ ${#extensions[@]} -gt 0 ]; then
    link_files "$root/tests/corpus" "$work/seeds" "${extensions[@]}"
    link_files "$meshes" "$work/seeds" "${extensions[@]}"
  fi
  seeds=("$work/seeds")
  for folder in "$here/seeds/$target" "$root/tests/regressions/$target"; do
    [ -d "$folder" ] && seeds+=("$folder")
  done
  echo "fuzz: $target for ${seconds}s"
  # One input may take at most FUZZ_TIMEOUT s and the process 1 GiB: inputs are at most
  # 16 KiB, so more means memory out of proportion to the input (a count believed before checking).
  if ! (cd "$work" && "$build/fuzz/$target" -max_total_time="$seconds" -timeout="${FUZZ_TIMEOUT:-10}" -rss_limit_mb=1024 \
          -max_len=16384 -print_final_stats=1 "$work/corpus" "${seeds[@]}" > "$work/log.txt" 2>&1); then
    tail -n 60 "$work/log.txt"
    echo "fuzz: $target found a problem; its input is in $work (log: $work/log.txt)"
    exit 1
  fi
  grep -E "^stat::(number_of_executed_units|peak_rss_mb)" "$work/log.txt" | sed "s/^/fuzz: $target /"
done
