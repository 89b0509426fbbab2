#!/bin/sh
# The four-ligament knee swept 0-120 degrees free against the same knee on the prescribed passive
# path (data/hra-knee/flexion.toml), one after the other on one machine: wall and CPU seconds of
# each and their ratio (issue 37's benchmark; docs/knee-model.md, "The HRA knees free"), as
# Markdown: tests/bench/record.sh writes it as docs/validation/free-vs-prescribed.md.
#
#   tests/bench/free_vs_prescribed.sh MODEL OUT [LIGSIM]
set -eu
model=$1
out=$2
ligsim=${3:-build/pipeline/ligsim}
here=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"

timed() {
  name=$1
  shift
  /usr/bin/time -f "%e %U %S" -o "$out/$name.time" "$ligsim" flexion --model "$model" \
    --out "$out/$name" --angles 0,30,60,90,120 --no-images "$@" >"$out/$name.log" 2>&1
}

# The bones' contact grids (and the free knee's articular one) are built once, before either is
# timed.
"$ligsim" flexion --model "$model" --out "$out/warm-up" --angles 0 --no-images \
  >"$out/warm-up.log" 2>&1
timed prescribed --config "$here/data/hra-knee/flexion.toml"
timed free
echo "| sweep 0-120 deg | wall s | CPU s |"
echo "| --- | ---: | ---: |"
for name in prescribed free; do
  read -r wall user system <"$out/$name.time"
  echo "| $name | $wall | $(echo "$user + $system" | bc) |"
done
read -r pw pu ps <"$out/prescribed.time"
read -r fw fu fs <"$out/free.time"
echo
echo "Free / prescribed: wall $(echo "scale=2; $fw / $pw" | bc), CPU $(echo "scale=2; ($fu + $fs) / ($pu + $ps)" | bc)."
