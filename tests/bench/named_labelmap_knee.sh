#!/bin/bash
# The HRA female knee from a label map with nothing written by hand: the map that
# KneeFromLabels.TheHraKneeIsBuiltFromItsNamesAloneAndFlexes makes (the atlas' bones, menisci
# and ligaments and a tibial cartilage rasterised at 0.3 x 0.3 x 1 mm under Slicer-style names),
# built as that test builds it (`ligsim build --labels seg.nii.gz --cell-size 1.2`: linear
# tets, the default) and as 10-node tets (`--order 2`, the footprints' rims kept), each flexed
# free from 0 to 120 degrees with no config. Prints, as Markdown, what each label was taken for,
# the cost and the estimated error of each, and each knee's path and ligaments per angle:
# tests/bench/record.sh writes them as docs/validation/named-labelmap-knee.md. Not a test: run
# it by hand (about half an hour on two cores).
#
#   tests/bench/named_labelmap_knee.sh OUT
#   LIGSIM=path/to/ligsim, TEST_PIPELINE=path/to/test_pipeline (defaults: under build/)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
TEST_PIPELINE=${TEST_PIPELINE:-$SRC/build/tests/pipeline/test_pipeline}

rm -rf "$OUT/tmp" "$OUT/quadratic" "$OUT"/*.times
mkdir -p "$OUT/tmp"
run test env TMPDIR="$OUT/tmp" LIGSIM_KEEP_TEST_FILES=1 "$TEST_PIPELINE" \
  --gtest_filter=KneeFromLabels.TheHraKneeIsBuiltFromItsNamesAloneAndFlexes
tmp=$(echo "$OUT"/tmp/ligsim_pipeline_*)
run flexion_linear "$LIGSIM" flexion --model "$tmp/hra_named_knee" --angles 0,30,60,90,120 \
  --no-images --out "$OUT/flexion_linear"
run build_quadratic "$LIGSIM" build --labels "$tmp/hra_named_map/seg.nii.gz" \
  --out "$OUT/quadratic" --cell-size 1.2 --order 2 --set ligament.tetmesh.footprint_rims=true \
  --no-images
run flexion_quadratic "$LIGSIM" flexion --model "$OUT/quadratic" --angles 0,30,60,90,120 \
  --no-images --out "$OUT/flexion_quadratic"
seconds() { cut -d' ' -f1 "$OUT/$1.times"; }
python3 "$(dirname "$0")/named_labelmap_knee_table.py" "$tmp/hra_named_knee" \
  "linear tets" "$OUT/flexion_linear" "$(seconds test) (the test: map, build and its own sweep)" \
  "$(seconds flexion_linear)" \
  "10-node tets" "$OUT/flexion_quadratic" "$(seconds build_quadratic)" \
  "$(seconds flexion_quadratic)"
