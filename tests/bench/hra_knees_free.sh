#!/bin/bash
# The two shipped knees as they are shipped: data/hra-knee/knee.toml (female) and knee-male.toml
# (male), each built and flexed free from 0 to 120 degrees with no flexion config, as a user
# runs them. Prints, as Markdown, each knee's build and sweep seconds and each ligament's
# largest estimated error, then each knee's path, articular contact and ligaments per angle:
# tests/bench/record.sh writes them as docs/validation/hra-knees-free.md. Not a test: run it by
# hand (about half an hour on two cores).
#
#   tests/bench/hra_knees_free.sh OUT
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

rm -f "$OUT"/*.times
for knee in female male; do
  config=$SRC/data/hra-knee/knee.toml
  [ "$knee" = male ] && config=$SRC/data/hra-knee/knee-male.toml
  run "build_$knee" "$LIGSIM" build --config "$config" --out "$OUT/$knee" --force --no-images
  run "flexion_$knee" "$LIGSIM" flexion --model "$OUT/$knee" --angles 0,30,60,90,120 \
    --no-images --out "$OUT/flexion_$knee"
done
seconds() { cut -d' ' -f1 "$OUT/$1.times"; }
python3 "$(dirname "$0")/knee_flexion_tables.py" \
  "female (knee.toml)" "$OUT/flexion_female" "$(seconds build_female)" "$(seconds flexion_female)" \
  "male (knee-male.toml)" "$OUT/flexion_male" "$(seconds build_male)" "$(seconds flexion_male)"
