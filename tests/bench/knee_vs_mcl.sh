#!/bin/bash
# The four-ligament HRA knee (data/hra-knee/knee.toml) against its MCL alone, side by side: the
# build of every stage (--force), the quasi-static sweep 0-120 degrees of data/hra-knee/
# flexion.toml, and the interactive sweep (its frames per second, from summary.json). ROUNDS
# rounds, each running every job once in turn (interleaved, so all see the same machine load);
# medians of wall time and peak resident memory (/usr/bin/time), the knee's ratio to the MCL,
# and the load average before and after. Not a test: run it by hand (several minutes per round;
# `nice` it on a shared machine).
#
#   tests/bench/knee_vs_mcl.sh OUT [ROUNDS]        (default 3 rounds)
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim); CONTACT=off sweeps without contact.
set -euo pipefail
OUT=$1
ROUNDS=${2:-3}

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
fps() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['results']['frames_per_second'])" "$1"; }

rm -f "$OUT"/*.times "$OUT"/*.fps
cd "$SRC"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for _ in $(seq "$ROUNDS"); do
  run build_knee "$LIGSIM" build --config data/hra-knee/knee.toml --out "$OUT/knee" --force
  run build_mcl "$LIGSIM" build --config data/hra-knee/mcl-female.toml --out "$OUT/mcl" --force
  for model in knee mcl; do
    run "static_$model" "$LIGSIM" flexion --model "$OUT/$model" --out "$OUT/static_$model" \
      --config data/hra-knee/flexion.toml --contact "$CONTACT" --no-images
    run "interactive_$model" "$LIGSIM" flexion --model "$OUT/$model" \
      --out "$OUT/interactive_$model" --config data/hra-knee/flexion.toml --contact "$CONTACT" \
      --mode interactive --no-images
    fps "$OUT/interactive_$model/summary.json" >> "$OUT/interactive_$model.fps"
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

printf "| job (contact %s) | knee: wall s | MCL: wall s | knee / MCL | knee: peak MiB | MCL: peak MiB |\n" "$CONTACT"
printf "| --- | ---: | ---: | ---: | ---: | ---: |\n"
for job in build static interactive; do
  compare_row "$job" "${job}_knee" "${job}_mcl"
done
printf "| interactive frames per second (median of %d) | %.1f | %.1f | | | |\n" "$ROUNDS" \
  "$(median < "$OUT/interactive_knee.fps")" "$(median < "$OUT/interactive_mcl.fps")"
