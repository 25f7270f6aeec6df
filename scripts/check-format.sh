#!/usr/bin/env bash
# Fails, listing the differences, when a tracked C++ or GLSL file differs from .clang-format.
# clang-format 14 (Debian 12's) is the reference: other versions format some constructs differently.
# With --fix, rewrites the files in place instead.
set -euo pipefail
cd "$(dirname "$0")/.."

formatter=clang-format-14
command -v "$formatter" >/dev/null || formatter=clang-format
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.comp' '*.glsl' '*.frag' '*.vert')

if [ "${1:-}" = "--fix" ]; then
  "$formatter" -i "${files[@]}"
else
  "$formatter" --dry-run --Werror "${files[@]}"
  echo "check-format: ${#files[@]} files match .clang-format"
fi
