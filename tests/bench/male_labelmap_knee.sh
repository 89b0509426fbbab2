#!/bin/bash
# The HRA male right knee from a label map with nothing written by hand: its closed femur (the
# atlas femur with the 15 meshes that fill its openings, as data/hra-knee/knee-male.toml), tibia,
# fibula and four ligaments rasterised by `ligsim labelmap` under Slicer-style names, 60 mm around
# the MCL. At the default 0.3 x 0.3 x 1 mm the build must refuse the PCL (the atlas PCL is a
# thread that falls apart between 1 mm slices; the refusal is printed); at 0.3 x 0.3 x 0.5 mm it
# builds with `ligsim build --labels seg.nrrd` alone and is flexed free with no config. Prints, as
# Markdown, the refusal, what each label was taken for, the cost and estimated error, and the
# path and ligaments per angle: tests/bench/record.sh writes them as
# docs/validation/male-labelmap-knee.md. Not a test: run it by hand (about 20 minutes on two
# cores).
#
#   tests/bench/male_labelmap_knee.sh OUT
#   LIGSIM=path/to/ligsim (default: build/pipeline/ligsim)
set -euo pipefail
OUT=$1

# shellcheck source=tests/bench/timed_runs.sh
source "$(dirname "$0")/timed_runs.sh"
atlas=$SRC/data/hra-knee
femur=$(sed -n 's/^femur = "\(.*\)"$/\1/p' "$atlas/knee-male.toml")
ligaments=$atlas/VH_M_Ligaments_Knee_R.glb
parts=(--part "$atlas/$femur:1:femur"
  --part "$atlas/VH_M_Knee_R.glb#VH_M_tibia_R:2:tibia"
  --part "$atlas/VH_M_Knee_R.glb#VH_M_fibula_R:3:fibula"
  --part "$ligaments#VH_M_right_tibial_collaterial_ligament:4:tibial_collateral_ligament"
  --part "$ligaments#VH_M_fibular_collateral_ligament_R:5:fibular_collateral_ligament"
  --part "$ligaments#VH_M_anterior_cruciate_ligament_of_knee_joint_R:6:anterior_cruciate_ligament"
  --part "$ligaments#VH_M_posterior_cruciate_ligament_of_knee_joint_R:7:posterior_cruciate_ligament")
around=(--around "$ligaments#VH_M_right_tibial_collaterial_ligament" --margin 60)

rm -rf "$OUT/map-1mm" "$OUT/knee-1mm" "$OUT/map" "$OUT/knee" "$OUT/flexion" "$OUT"/*.times
run map_1mm "$LIGSIM" labelmap "${parts[@]}" "${around[@]}" --out "$OUT/map-1mm/seg.nrrd"
if "$LIGSIM" build --labels "$OUT/map-1mm/seg.nrrd" --out "$OUT/knee-1mm" --no-images \
  > "$OUT/build_1mm.out" 2>&1; then
  echo "$(basename "$0"): the build of the 1 mm map was to refuse the PCL, and did not" >&2
  exit 1
fi
run map "$LIGSIM" labelmap "${parts[@]}" "${around[@]}" --spacing 0.3,0.3,0.5 \
  --out "$OUT/map/seg.nrrd"
run build "$LIGSIM" build --labels "$OUT/map/seg.nrrd" --out "$OUT/knee" --no-images
run flexion "$LIGSIM" flexion --model "$OUT/knee" --no-images --out "$OUT/flexion"

echo "At 0.3 x 0.3 x 1 mm, \`ligsim build --labels seg.nrrd\` stops before any stage:"
echo
echo '```text'
grep 'error:' "$OUT/build_1mm.out" | sed "s|$OUT/||g"
echo '```'
echo
echo "At 0.3 x 0.3 x 0.5 mm it builds; the map's labels were taken for:"
echo
seconds() { cut -d' ' -f1 "$OUT/$1.times"; }
python3 "$(dirname "$0")/named_labelmap_knee_table.py" "$OUT/knee" \
  "0.3 x 0.3 x 0.5 mm map, linear tets" "$OUT/flexion" "$(seconds build)" "$(seconds flexion)"
