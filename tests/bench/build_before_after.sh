#!/bin/bash
# Time and peak memory of `ligsim build` from two binaries (BEFORE, e.g. main's, and AFTER),
# run one after the other on each case, so both see the same machine load: the real MCL
# (data/vhf-right-knee) and the synthetic band (`ligsim synth band`), at the default voxel
# and at the given voxel sizes. Not a test: run it by hand (long; `nice` it on a shared machine).
#
#   tests/bench/build_before_after.sh BEFORE AFTER OUT [VOXEL...]   (default voxels: 0.09 0.05)
#   CASES="mcl band" limits the samples; SKIP="before:band:0.05 ..." leaves cases out;
#   UNTIL="before:mcl:0.05:centerline ..." runs that case only as far as the named stage
#   (`ligsim <stage>`); TIMEOUT=SECONDS stops a run that takes longer (the stages it finished
#   still show).
#
# Writes OUT/<tag>-<sample>-<voxel>/ (the build, its summary.json and stage records),
# OUT/<tag>-<sample>-<voxel>.time (/usr/bin/time -v) and OUT/table.md: per run the stages'
# wall time summed and the largest of the stages' peak RSS (ligsim resets the peak at each
# stage's start and records it in .ligsim-cache/<stage>.json), the process's maximum resident
# set as /usr/bin/time reports it (the kernel's, which the resets may lower below the true
# peak: the stages' figure is the one to trust) and the voxel stages' time and peak.
set -euo pipefail
BEFORE=$1 AFTER=$2 OUT=$3
shift 3
VOXELS=${*:-0.09 0.05}
CASES=${CASES:-mcl band}
SKIP=${SKIP:-}
UNTIL=${UNTIL:-}
SRC=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

# Both binaries read the same config; max_voxels is raised so that main's box guard (3e7 box
# voxels) lets the 0.05 mm runs through (ours counts inside voxels).
data=$SRC/data/vhf-right-knee
sed "s#^surface = \"#surface = \"$data/#; s#^tibia = \"#tibia = \"$data/#; s#^femur = \"#femur = \"$data/#" \
  "$data/mcl.toml" > "$OUT/mcl.toml"
printf '\n[voxelize]\nmax_voxels = 3e8\n' >> "$OUT/mcl.toml"
[ -f "$OUT/band/surface.stl" ] || "$AFTER" synth band --out "$OUT/band" > /dev/null
printf '[input]\nsurface = "%s/band/surface.stl"\nfemur = "%s/band/femur.stl"\ntibia = "%s/band/tibia.stl"\n\n[voxelize]\nmax_voxels = 3e8\n' \
  "$OUT" "$OUT" "$OUT" > "$OUT/band.toml"

run() { # tag binary sample voxel
  local dir=$OUT/$1-$3-$4
  case " $SKIP " in *" $1:$3:$4 "*) echo "skipped $1 $3 $4"; return ;; esac
  local voxel_arg=() target=build
  [ "$4" != default ] && voxel_arg=(--voxel "$4")
  for until in $UNTIL; do
    [ "${until%:*}" = "$1:$3:$4" ] && target=${until##*:}
  done
  rm -rf "$dir"
  echo "$1 $3 $4 ($target) ..." >&2
  /usr/bin/time -v -o "$dir.time" timeout "${TIMEOUT:-0}" \
    "$2" "$target" --config "$OUT/$3.toml" "${voxel_arg[@]}" --out "$dir" > "$dir.log" 2>&1 ||
    echo "$1 $3 $4 failed or stopped (see $dir.log)" >&2
}

for sample in $CASES; do
  for voxel in default $VOXELS; do
    run before "$BEFORE" "$sample" "$voxel"
    run after "$AFTER" "$sample" "$voxel"
  done
done

python3 - "$OUT" > "$OUT/table.md" << 'EOF'
import json, pathlib, re, sys
out = pathlib.Path(sys.argv[1])
stages = ["voxelize", "distance", "centerline", "field"]
print("| sample | voxel (mm) | code | stages run | wall (s) | peak (MiB) | time -v max RSS (MiB) | "
      + " | ".join(f"{s} (s / MiB)" for s in stages) + " |")
print("|---" * (7 + len(stages)) + "|")
for run in sorted(p for p in out.iterdir() if (p / ".ligsim-cache").is_dir()):
    tag, sample, voxel = run.name.split("-", 2)
    records = {f.stem: json.loads(f.read_text()) for f in (run / ".ligsim-cache").glob("*.json")}
    if not records:
        continue
    wall = sum(r["wall_s"] for r in records.values())
    peak = max(r["peak_rss_mib"] for r in records.values())
    time_v = (out / f"{run.name}.time")
    found = re.search(r"Maximum resident set size \(kbytes\): (\d+)", time_v.read_text()) if time_v.exists() else None
    max_rss = f"{int(found.group(1)) / 1024:.0f}" if found else "-"
    cells = [f"{records[s]['wall_s']:.1f} / {records[s]['peak_rss_mib']:.0f}" if s in records else "-"
             for s in stages]
    print(f"| {sample} | {voxel} | {tag} | {len(records)} | {wall:.1f} | {peak:.0f} | {max_rss} | "
          + " | ".join(cells) + " |")
EOF
cat "$OUT/table.md"
