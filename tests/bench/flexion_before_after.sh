#!/bin/bash
# Interactive flexion frames per second (bench_flexion, the shipped max_iterations 12) of two
# builds side by side: ROUNDS rounds,
# each running every case (contact off, d_hat 0.3 mm, d_hat 1 mm) with BEFORE's and AFTER's
# bench_flexion in turn (interleaved, so both see the same machine load); medians of the frames
# per second and of the main thread's CPU time of the sweep. Each case reads its own copy of the
# model so that its contact grids (their band depends on d_hat) are built once, not at every run.
# Not a test: run it by hand (about 30 s per round; `nice` it on a shared machine).
#
#   tests/bench/flexion_before_after.sh BEFORE AFTER MODEL OUT [ROUNDS]   (default 5 rounds)
#   BEFORE, AFTER: bench_flexion executables; MODEL: a built model folder (out/mcl6k, see
#   flexion_bench.cpp). Writes OUT/runs.txt (round, build, case, fps, CPU ms, load) and prints
#   the medians.
set -euo pipefail
BEFORE=$1 AFTER=$2 MODEL=$3 OUT=$4
ROUNDS=${5:-5}
mkdir -p "$OUT"
for arg in 0 3 10; do
  [ -d "$OUT/model-$arg" ] || cp -r "$MODEL" "$OUT/model-$arg"
done
: > "$OUT/runs.txt"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for round in $(seq "$ROUNDS"); do
  for arg in 0 3 10; do
    for build in before after; do
      binary=$BEFORE
      [ "$build" = after ] && binary=$AFTER
      line=$(LIGSIM_BENCH_MODEL="$OUT/model-$arg" "$binary" --benchmark_filter="/$arg/12/" 2>&1 |
        grep '^BM_')
      fps=$(echo "$line" | grep -o 'frames_per_second=[0-9.]*' | cut -d= -f2)
      cpu=$(echo "$line" | awk '{print $4}')
      echo "$round $build $arg $fps $cpu $(cut -d' ' -f1 /proc/loadavg)" >> "$OUT/runs.txt"
    done
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$OUT/runs.txt" <<'EOF'
import collections, statistics, sys
fps, cpu = collections.defaultdict(list), collections.defaultdict(list)
for line in open(sys.argv[1]):
    _, build, arg, f, c, _ = line.split()
    fps[(build, int(arg))].append(float(f))
    cpu[(build, int(arg))].append(float(c))
print("| build | case | fps (median) | main thread CPU ms (median) | cost of contact (fps) |")
print("| --- | --- | ---: | ---: | ---: |")
for build in ("before", "after"):
    off = statistics.median(fps[(build, 0)])
    for arg in (0, 3, 10):
        f = statistics.median(fps[(build, arg)])
        case = "no contact" if arg == 0 else f"d_hat {arg / 10} mm"
        cost = "" if arg == 0 else f"{100 * (1 - f / off):.1f} %"
        print(f"| {build} | {case} | {f:.1f} | {statistics.median(cpu[(build, arg)]):.0f} | {cost} |")
EOF
