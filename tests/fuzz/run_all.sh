#!/usr/bin/env bash
# Runs the libFuzzer targets of tests/fuzz for SECONDS each (default 600), two at a time, at
# nice 19, each capped at 2 GB RSS and 10 s per input, and prints a Markdown table per target:
# executions, executions per second, corpus (files, coverage) and findings (crash, timeout,
# out-of-memory and leak reproducers left in OUT/<target>/artifacts/).
#
# usage: tests/fuzz/run_all.sh BUILD_FUZZ_DIR OUT_DIR [SECONDS] [TARGET ...]
#   BUILD_FUZZ_DIR  a build with -DLIGSIM_FUZZ=ON (see docs/development.md, "Fuzzing")
#   OUT_DIR         per target: the corpus it grew, its log and its artifacts; table.md
#   TARGET          default: every fuzz_* target
set -euo pipefail

build=${1:?usage: run_all.sh BUILD_FUZZ_DIR OUT_DIR [SECONDS] [TARGET ...]}
out=${2:?usage: run_all.sh BUILD_FUZZ_DIR OUT_DIR [SECONDS] [TARGET ...]}
seconds=${3:-600}
shift $(($# < 3 ? $# : 3))
source_dir=$(cd "$(dirname "$0")" && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_surface_stl fuzz_surface_obj fuzz_surface_ply fuzz_surface_vtp fuzz_surface_vtk
           fuzz_surface_gltf
           fuzz_label_map_nrrd fuzz_label_map_mha fuzz_build_config fuzz_flexion_config
           fuzz_simulate_scene fuzz_tear_scene)
fi

seeds_of() {
  case $1 in
    fuzz_surface_*) echo "$source_dir/corpus/${1#fuzz_surface_}" ;;
    fuzz_label_map_*) echo "$source_dir/corpus/label_${1#fuzz_label_map_}" ;;
    *) echo "$build/tests/fuzz/seeds/${1#fuzz_}" ;;
  esac
}

run_one() {
  local target=$1 dir="$out/$1"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  nice -n 19 "$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$dir/artifacts/" \
    "$dir/corpus" "$(seeds_of "$target")" >"$dir/log.txt" 2>&1 || true
  local executions rate status corpus coverage findings
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log.txt" | tail -1)
  status=$(grep -E '(INITED|NEW|REDUCE|pulse|DONE) .*cov:' "$dir/log.txt" | tail -1 || true)
  corpus=$(echo "$status" | sed -n 's/.*corp: \([0-9]*\/[0-9a-zA-Z]*\).*/\1/p')
  coverage=$(echo "$status" | sed -n 's/.*cov: \([0-9]*\).*/\1/p')
  findings=$(find "$dir/artifacts" -type f | wc -l)
  echo "| $target | $seconds | ${executions:-?} | ${rate:-?} | ${corpus:-?} | ${coverage:-?} | $findings |" \
    >"$dir/row.md"
}

# Leaks of VTK and ITK on their own error paths, listed and explained there.
export LSAN_OPTIONS="suppressions=$source_dir/../lsan_suppressions.txt${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
mkdir -p "$out"
running=0
for target in "${targets[@]}"; do
  if [ $running -ge 2 ]; then
    wait -n
    running=$((running - 1))
  fi
  echo "$(date -u +%H:%M:%S) $target: ${seconds} s" >&2
  run_one "$target" &
  running=$((running + 1))
done
wait

{
  echo "| target | seconds | executions | exec/s | corpus (files/bytes) | coverage (edges) | findings |"
  echo "|---|---|---|---|---|---|---|"
  for target in "${targets[@]}"; do cat "$out/$target/row.md"; done
} | tee "$out/table.md"
