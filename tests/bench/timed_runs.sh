# Shared by the side-by-side benchmark scripts (sourced once OUT is set):
#   run NAME COMMAND...  runs COMMAND, its output in OUT/NAME.out, and appends "wall_s peak_kib"
#                        (/usr/bin/time) to OUT/NAME.times; stops the script if it fails.
#   median               the median of the numbers on stdin, one per line.

run() {
  local name=$1
  shift
  /usr/bin/time -f "%e %M" -o "$OUT/$name.time" "$@" > "$OUT/$name.out" 2>&1 ||
    { echo "$(basename "$0"): $name failed, see $OUT/$name.out" >&2; exit 1; }
  cat "$OUT/$name.time" >> "$OUT/$name.times"
}

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
