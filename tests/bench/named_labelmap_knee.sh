#!/bin/bash
# The HRA female knee from a label map with nothing written by hand: the map that
# KneeFromLabels.TheHraKneeIsBuiltFromItsNamesAloneAndFlexes makes (the atlas' bones, menisci
# and ligaments and a tibial cartilage rasterised at 0.3 x 0.3 x 1 mm under Slicer-style names),
# built as that test builds it (`ligsim build --labels seg.nii.gz --cell-size 1.2`), then
# flexed free from 0 to 120 degrees with no config. Prints the knee's path and its ligaments as
# Markdown: tests/bench/record.sh writes them as docs/validation/named-labelmap-knee.md. Not a
# test: run it by hand (about ten minutes on two cores).
#
#   tests/bench/named_labelmap_knee.sh OUT
#   LIGSIM=path/to/ligsim, TEST_PIPELINE=path/to/test_pipeline (defaults: under build/)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
TEST_PIPELINE=${TEST_PIPELINE:-$SRC/build/tests/pipeline/test_pipeline}

rm -rf "$OUT/tmp" "$OUT"/*.times
mkdir -p "$OUT/tmp"
run build env TMPDIR="$OUT/tmp" LIGSIM_KEEP_TEST_FILES=1 "$TEST_PIPELINE" \
  --gtest_filter=KneeFromLabels.TheHraKneeIsBuiltFromItsNamesAloneAndFlexes
knee=$(echo "$OUT"/tmp/ligsim_pipeline_*/hra_named_knee)
run flexion "$LIGSIM" flexion --model "$knee" --angles 0,30,60,90,120 --no-images \
  --out "$OUT/flexion"
printf "The test (map, build, its own sweep to 120 degrees) took %.0f s; the sweep below %.0f s.\n\n" \
  "$(cut -d' ' -f1 "$OUT/build.times")" "$(cut -d' ' -f1 "$OUT/flexion.times")"
python3 "$(dirname "$0")/named_labelmap_knee_table.py" "$knee" "$OUT/flexion"
