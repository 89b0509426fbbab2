#!/bin/sh
# Laxity and sectioning tests of a free knee, as testing machines and robots run them on cadaver
# knees: the knee flexed free to 0, 15 and 30 degrees, unloaded (20 N of compression), then under
# a 100 N anterior or posterior force, a 10 N m valgus or varus moment, a 5 N m internal or
# external moment; then with the ACL cut, unloaded, under the anterior force and under the valgus
# moment (Lujan et al., J Biomech Eng 2007;129:386). Prints the tables as Markdown:
# tests/bench/record.sh writes them as docs/validation/knee-laxity.md.
#
#   tests/bench/knee_laxity.sh MODEL OUT [LIGSIM]
#
# MODEL: a built four-ligament knee (`ligsim build --config data/hra-knee/knee.toml --out MODEL`);
# OUT: a folder for the runs (a run already there is kept). Two runs at a time.
set -eu
model=$1
out=$2
ligsim=${3:-build/pipeline/ligsim}
here=$(dirname "$0")
mkdir -p "$out"

run() {
  name=$1
  shift
  if [ ! -f "$out/$name/kinematics.csv" ]; then
    echo "knee_laxity: $name" >&2
    "$ligsim" flexion --model "$model" --out "$out/$name" --angles 0,15,30 --no-images "$@" \
      >"$out/$name.log" 2>&1 || echo "knee_laxity: $name failed: $out/$name.log" >&2
  fi
}

run intact & run anterior --load anterior_n=100 & wait
run posterior --load anterior_n=-100 & run valgus --load valgus_nm=10 & wait
run varus --load valgus_nm=-10 & run internal --load internal_nm=5 & wait
run external --load internal_nm=-5 & run acl-cut --without ACL & wait
run acl-cut-anterior --without ACL --load anterior_n=100 &
run acl-cut-valgus --without ACL --load valgus_nm=10 & wait
python3 "$here/knee_laxity_table.py" "$out"
