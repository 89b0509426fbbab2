#!/usr/bin/env bash
# Fails, naming the files, if the core (common/, stages/, sim/) reaches for rendering or a display:
# a header of one of VTK's rendering modules, an X server, or the rendering libraries in its
# CMake files. Pictures and windows belong to pipeline/render and pipeline/view. Also fails where
# a header of sim/ includes nlohmann/json (results are typed there and written as JSON in
# pipeline/reports) or VTK (the simulator's types are its own: bones are TriangleSurface; VTK
# data sets are built in its .cpp files, where it writes them, and at the edge).
# Arguments: the hierarchy files of VTK's rendering modules.
set -euo pipefail
cd "$(dirname "$0")/.."
(($# > 0)) || { echo "usage: $0 <vtk rendering module hierarchy files>" >&2; exit 2; }

# A hierarchy line reads "class : base ; header.h ; module"; it also lists the classes a module
# uses from others, so only the headers of the module itself count.
headers=$(for file in "$@"; do
  module=$(basename "$file" -hierarchy.txt)
  awk -F' ; ' -v module="$module" '$3 == module { print $2 }' "$file"
done | sort -u)
[[ -n "$headers" ]] || { echo "no VTK rendering headers read from: $*" >&2; exit 2; }
pattern="#include[[:space:]]*[<\"]($(sed 's/\./\\./' <<<"$headers" | paste -sd'|'))[>\"]"

status=0
core_sources() { find common stages sim \( -name '*.cpp' -o -name '*.hpp' \) -print0; }
if found=$(core_sources | xargs -0 grep -nE "$pattern"); then
  echo "the core includes VTK rendering headers (move the code to pipeline/render):" >&2
  echo "$found" >&2
  status=1
fi
if found=$(core_sources | xargs -0 grep -nE 'Xvfb|"DISPLAY"|<X11/'); then
  echo "the core deals with an X display (pipeline/render/offscreen_display does):" >&2
  echo "$found" >&2
  status=1
fi
if found=$(find sim -name '*.hpp' -print0 | xargs -0 grep -nE '#include[[:space:]]*<nlohmann/'); then
  echo "a simulator header includes nlohmann/json (type the result in sim/, write its JSON in" >&2
  echo "pipeline/reports):" >&2
  echo "$found" >&2
  status=1
fi
if found=$(find sim -name '*.hpp' -print0 | xargs -0 grep -nE '#include[[:space:]]*<vtk|^class vtk'); then
  echo "a simulator header includes or declares VTK (keep VTK in the .cpp files; give the header" >&2
  echo "the project's own types):" >&2
  echo "$found" >&2
  status=1
fi
if found=$(find common stages sim -name CMakeLists.txt -print0 |
  xargs -0 grep -nE 'LIGSIM_VTK_RENDERING|VTK_LIBRARIES|X11::|ligsim_render|ligsim_view'); then
  echo "a core library links rendering or a display (link \${LIGSIM_VTK_DATA} only):" >&2
  echo "$found" >&2
  status=1
fi
exit "$status"
