#!/usr/bin/env bash
# Runs every fuzz target of a MEANDER_BUILD_FUZZ build one after the other (each on one
# core), and stops at the first finding, leaving its input in BUILD/fuzz-runs/TARGET/ as
# libFuzzer names it (crash-*, leak-*, timeout-*, oom-*).
# Usage: fuzz/run.sh BUILD SECONDS [TARGET...]
#          (make fuzz) fuzzes each target SECONDS, from and into BUILD/fuzz-runs/TARGET/
#          corpus/, which a later run starts from. FUZZ_TIMEOUT (default 10) is the
#          seconds of wall clock one input may take: raise it for runs niced beside other
#          work, where a starved fuzzer waits for a core.
#        fuzz/run.sh BUILD --merge [TARGET...]
#          (make fuzz-corpus) replaces fuzz/corpus/TARGET/, the corpus committed and
#          replayed by make test, with the smallest set of its inputs and those of
#          BUILD/fuzz-runs/TARGET/corpus/ (make fuzz's) that covers what they all cover
#          (libFuzzer -merge=1).
#        fuzz/run.sh BUILD --runs N [TARGET...]
#          (make test) runs every seed, then N inputs more made from a fixed seed into a
#          fresh corpus: the same inputs on any machine, busy or not. For that the target
#          runs on one core (oneTBB then runs no thread of its own), without address
#          randomisation, and libFuzzer takes no values from the program's comparisons
#          (some compare clocks or addresses). No limit there that load decides: an input
#          may take 20 minutes (only a hang takes that long), and memory is limited per
#          allocation (1 GiB) rather than by resident size. Runs still part ways now and
#          then where coverage follows the sanitizer allocator's addresses, and in
#          fuzz_studio_http, whose server draws its session keys at random.
# Seeds: fuzz/seeds/TARGET/ (hand-made), fuzz/corpus/TARGET/ (minimised from long runs), the files of tests/corpus/ and the small meshes
# of ../shared/meshes with the target's extension (linked in place, not copied), and the
# regressions of tests/regressions/TARGET/.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=$(cd "$1" && pwd)
merge=
if [ "$2" = --runs ]; then
  runs=$3 seconds=
  shift 3
elif [ "$2" = --merge ]; then
  merge=1 runs= seconds=
  shift 2
else
  runs= seconds=$2
  shift 2
fi
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_read_obj fuzz_read_ply fuzz_read_stl fuzz_read_off fuzz_read_gltf fuzz_repair fuzz_curve fuzz_wire fuzz_duotone fuzz_textured_obj fuzz_image fuzz_studio_request fuzz_studio_upload fuzz_studio_http)
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

# The first core this process may use, and no address randomisation where the system
# lets a process turn it off.
one_core=(taskset -c "$(taskset -pc $$ | sed 's/.*: //; s/[,-].*//')")
setarch "$(uname -m)" -R true 2> /dev/null && one_core=(setarch "$(uname -m)" -R "${one_core[@]}")

for target in "${targets[@]}"; do
  work=$build/fuzz-runs/$target
  if [ -n "$merge" ]; then
    merged=$work/merged
    rm -rf "$merged" && mkdir -p "$merged" "$here/corpus/$target" "$work/corpus"
    "$build/fuzz/$target" -merge=1 -max_len=16384 -rss_limit_mb=1024 "$merged" "$here/corpus/$target" "$work/corpus" > "$work/merge.txt" 2>&1 ||
      { tail -n 30 "$work/merge.txt"; exit 1; }
    rm -rf "$here/corpus/$target" && mv "$merged" "$here/corpus/$target"
    echo "fuzz: $target: $(ls "$here/corpus/$target" | wc -l) inputs in fuzz/corpus/$target"
    continue
  fi
  mkdir -p "$work/seeds"
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
  for folder in "$here/seeds/$target" "$here/corpus/$target" "$root/tests/regressions/$target"; do
    [ -d "$folder" ] && seeds+=("$folder")
  done
  # An input is at most 16 KiB: 1 GiB of memory is out of proportion to it (a count
  # believed before checking).
  common=(-max_len=16384 -print_final_stats=1)
  if [ -n "$runs" ]; then
    # -runs counts the seeds' runs too; -reload=0: the corpus is not read again on a clock.
    corpus=$work/check-corpus
    rm -rf "$corpus" && mkdir -p "$corpus"
    count=$(find -L "${seeds[@]}" -type f | wc -l)
    # fuzz_image soon makes inputs that decode pictures of up to 16384 x 16384 pixels,
    # seconds each under the sanitizers: a tenth of the runs, at most 2,000.
    target_runs=$runs
    [ "$target" = fuzz_image ] && target_runs=$(( runs / 10 < 2000 ? runs / 10 : 2000 ))
    echo "fuzz: $target: $count seeds, then $target_runs runs from seed 1"
    flags=(-runs=$((count + target_runs)) -seed=1 -reload=0 -use_cmp=0 -use_memmem=0 -timeout=1200 -rss_limit_mb=0 -malloc_limit_mb=1024)
    fixed=("${one_core[@]}")
  else
    corpus=$work/corpus
    mkdir -p "$corpus"
    echo "fuzz: $target for ${seconds}s"
    flags=(-max_total_time="$seconds" -timeout="${FUZZ_TIMEOUT:-10}" -rss_limit_mb=1024)
    fixed=()
  fi
  if ! (cd "$work" && "${fixed[@]}" "$build/fuzz/$target" "${flags[@]}" "${common[@]}" "$corpus" "${seeds[@]}" > "$work/log.txt" 2>&1); then
    tail -n 60 "$work/log.txt"
    echo "fuzz: $target found a problem; its input is in $work (log: $work/log.txt)"
    exit 1
  fi
  grep -E "^stat::(number_of_executed_units|peak_rss_mb)" "$work/log.txt" | sed "s/^/fuzz: $target /"
done
