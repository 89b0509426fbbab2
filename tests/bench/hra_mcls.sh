#!/bin/bash
# The README's two commands on both atlas knees' MCL: data/hra-knee/mcl-female.toml and
# mcl-male.toml built, then flexed from 0 to 120 degrees on data/hra-knee/flexion.toml's path
# (without pictures, to time the simulation). Prints, as Markdown, each model's size and cost,
# then its fiber strain, pull on the femur and length change per angle with their error
# estimates: tests/bench/record.sh writes them as docs/validation/hra-mcls.md. Not a test: run it
# by hand (about 25 minutes on two cores).
#
#   tests/bench/hra_mcls.sh OUT
#   LIGSIM=path/to/ligsim (default build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"

rm -f "$OUT"/*.times
for knee in female male; do
  run "build_$knee" "$LIGSIM" build --config "$SRC/data/hra-knee/mcl-$knee.toml" \
    --out "$OUT/$knee" --force --no-images
  run "flexion_$knee" "$LIGSIM" flexion --config "$SRC/data/hra-knee/flexion.toml" \
    --model "$OUT/$knee" --no-images --out "$OUT/flexion_$knee"
done
python3 "$(dirname "$0")/mcl_flexion_tables.py" \
  "female (mcl-female.toml)" "$OUT/female" "$OUT/flexion_female" "$OUT/build_female.times" \
  "$OUT/flexion_female.times" \
  "male (mcl-male.toml)" "$OUT/male" "$OUT/flexion_male" "$OUT/build_male.times" \
  "$OUT/flexion_male.times"
