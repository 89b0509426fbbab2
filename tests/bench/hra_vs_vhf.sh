#!/bin/bash
# The shipped whole knee's MCL (data/hra-knee/mcl-female.toml, flexion.toml: 0-120 degrees on
# the passive path) against the MRI sample's (data/vhf-right-knee/mcl.toml, flexion.toml: 0-90
# degrees), side by side: the quasi-static sweep and the interactive sweep (its frames per
# second, from summary.json), contact on, no pictures. The models are built once; then ROUNDS
# rounds run every job once in turn (interleaved, so all see the same machine load): medians of
# wall time and peak resident memory (/usr/bin/time), the HRA/VHF ratio, the load average before
# and after. Not a test: run it by hand (about five minutes per round).
#
#   tests/bench/hra_vs_vhf.sh OUT [ROUNDS]        (default 3 rounds)
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1
ROUNDS=${2:-3}

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
fps() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['results']['frames_per_second'])" "$1"; }
tets() { python3 -c "import json,sys; [l] = json.load(open(sys.argv[1]))['results']['ligaments'].values(); print(l['setup']['tets'])" "$1"; }

rm -f "$OUT"/*.times "$OUT"/*.fps
cd "$SRC"
run build_hra "$LIGSIM" build --config data/hra-knee/mcl-female.toml --out "$OUT/hra"
run build_vhf "$LIGSIM" build --config data/vhf-right-knee/mcl.toml --out "$OUT/vhf"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for _ in $(seq "$ROUNDS"); do
  for knee in hra vhf; do
    config=data/hra-knee/flexion.toml
    [ $knee = vhf ] && config=data/vhf-right-knee/flexion.toml
    run "static_$knee" "$LIGSIM" flexion --model "$OUT/$knee" --out "$OUT/static_$knee" \
      --config "$config" --no-images
    run "interactive_$knee" "$LIGSIM" flexion --model "$OUT/$knee" \
      --out "$OUT/interactive_$knee" --config "$config" --mode interactive --no-images
    fps "$OUT/interactive_$knee/summary.json" >> "$OUT/interactive_$knee.fps"
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

printf "| job | HRA MCL (%s tets): wall s | VHF MCL (%s tets): wall s | HRA / VHF | HRA: peak MiB | VHF: peak MiB |\n" \
  "$(tets "$OUT/static_hra/summary.json")" "$(tets "$OUT/static_vhf/summary.json")"
printf "| --- | ---: | ---: | ---: | ---: | ---: |\n"
for job in static interactive; do
  compare_row "$job sweep" "${job}_hra" "${job}_vhf"
done
printf "| interactive frames per second (median of %d) | %.2f | %.2f | | | |\n" "$ROUNDS" \
  "$(median < "$OUT/interactive_hra.fps")" "$(median < "$OUT/interactive_vhf.fps")"
