#!/bin/sh
# Frames per second of `ligsim view` with the simulation running (issue 39's benchmark): the
# scripted drag 0 -> 90 degrees in 2 s and a 1 s hold (300 frames of 10 ms), drawn without
# recording, on the 6,141-tet VHF MCL and on the four-ligament HRA knee built for live use, at
# two window sizes; beside the MCL's frames computed alone by bench_flexion (no window), one
# after the other on one machine. Needs xvfb-run unless $DISPLAY is set.
#
#   tests/bench/view_fps.sh OUT [BUILD_DIR]
set -eu
out=$1
build=${2:-build}
ligsim=$build/pipeline/ligsim
here=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"

[ -f "$out/mcl6k/model.vtu" ] ||
  "$ligsim" build --config "$here/data/vhf-right-knee/mcl.toml" --cell-size 1.1 \
    --facet-size 0.95 --facet-distance 0.08 --no-images --out "$out/mcl6k" >"$out/build.log" 2>&1
[ -f "$out/knee-live/knee.json" ] ||
  "$ligsim" build --config "$here/data/hra-knee/knee.toml" --cell-size 2.5 --facet-size 2.5 \
    --facet-distance 0.3 --no-images --out "$out/knee-live" >>"$out/build.log" 2>&1
printf "time_s,angle_deg\n0,0\n2,90\n3,90\n" >"$out/drag.csv"

screen=""
[ -n "${DISPLAY:-}" ] || screen="xvfb-run -a -s -screen\ 0\ 1280x1024x24"

echo "| model | window | drawn per s | computed per s |"
echo "| --- | --- | ---: | ---: |"
for model in mcl6k:data/vhf-right-knee/flexion.toml knee-live:data/hra-knee/flexion.toml; do
  name=${model%%:*}
  config=$here/${model#*:}
  for size in 1024 640; do
    line=$(eval $screen "$ligsim" view --config "$config" --model "$out/$name" \
      --script "$out/drag.csv" --size $size 2>&1 | grep "frames in")
    drawn=$(echo "$line" | sed 's/.*: \([0-9.]*\) frames\/s drawn.*/\1/')
    computed=$(echo "$line" | sed 's/.*, \([0-9.]*\) computed.*/\1/')
    echo "| $name | $size x $((size * 3 / 4)) | $drawn | $computed |"
  done
done
LIGSIM_BENCH_MODEL=$out/mcl6k "$build/tests/bench/bench_flexion" \
  --benchmark_filter='BM_InteractiveFlexion/3/12' 2>/dev/null | grep BM_
