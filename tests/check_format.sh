#!/usr/bin/env bash
# Fails, naming the files, if a C++ source of the tree is not formatted as .clang-format says.
# Fix with: clang-format -i <files>
set -euo pipefail
cd "$(dirname "$0")/.."
find common pipeline stages sim tests \( -name '*.cpp' -o -name '*.hpp' \) -print0 |
  xargs -0 "${CLANG_FORMAT:-clang-format}" --dry-run --Werror
