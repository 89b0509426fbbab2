# shellcheck shell=bash
# Shared by the side-by-side benchmark scripts (sourced once OUT is set). Sets SRC (the source
# tree), LIGSIM (default build/pipeline/ligsim) and CONTACT (default on), and makes OUT an
# absolute path to a folder that exists. Then:
#   run NAME COMMAND...  runs COMMAND, its output in OUT/NAME.out, and appends "wall_s peak_kib"
#                        (/usr/bin/time) to OUT/NAME.times; stops the script if it fails.
#   median               the median of the numbers on stdin, one per line.
#   compare_row LABEL A B  a table row: the median wall seconds of runs A and B, their ratio
#                        A / B, and their median peak MiB.

SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
LIGSIM=${LIGSIM:-$SRC/build/pipeline/ligsim}
CONTACT=${CONTACT:-on}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

run() {
  local name=$1
  shift
  /usr/bin/time -f "%e %M" -o "$OUT/$name.time" "$@" > "$OUT/$name.out" 2>&1 ||
    { echo "$(basename "$0"): $name failed, see $OUT/$name.out" >&2; exit 1; }
  cat "$OUT/$name.time" >> "$OUT/$name.times"
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

compare_row() {
  local aw bw am bm
  aw=$(cut -d' ' -f1 "$OUT/$2.times" | median)
  bw=$(cut -d' ' -f1 "$OUT/$3.times" | median)
  am=$(cut -d' ' -f2 "$OUT/$2.times" | median | awk '{print $1 / 1024}')
  bm=$(cut -d' ' -f2 "$OUT/$3.times" | median | awk '{print $1 / 1024}')
  printf "| %s | %.1f | %.1f | %.2f | %.0f | %.0f |\n" "$1" "$aw" "$bw" "$(echo "$aw / $bw" | bc -l)" "$am" "$bm"
}
