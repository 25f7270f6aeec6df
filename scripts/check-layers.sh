#!/usr/bin/env bash
# Fails, listing them, when an include runs back up a layer (docs/architecture.md "Layers"): a file may include
# headers of its own layer and of the layers below it, never of one above. An include names its folder
# ("model/film.h" inside cpu-reference/, "capture/hand_finder.h" from the project's root), and one that does not fails
# too, but inside kernels/, whose headers GLSL includes by name as well. A header is looked up by its file name among
# the tracked headers (a name two folders hold is left out). Inside cpu-reference/ the folders are layers too,
# from the bottom: model, solver, stages, topology, simulation; the includes that still run back up there are listed
# in `known` below, and any other fails.
set -euo pipefail
cd "$(dirname "$0")/.."

rank() {
  case "$1" in
    kernels/*) echo 10 ;;
    cpu-reference/model/*) echo 21 ;;
    cpu-reference/solver/*) echo 22 ;;
    cpu-reference/stages/*) echo 23 ;;
    cpu-reference/topology/*) echo 24 ;;
    cpu-reference/simulation/*) echo 25 ;;
    research/* | host/* | capture/*) echo 30 ;;
    scene/*) echo 40 ;;
    app/*) echo 50 ;;
    tests/* | bench/*) echo 60 ;;
    *) echo 0 ;;
  esac
}

# The includes that still run back up inside cpu-reference/: the step's vocabulary in stages.h (the geometry, the
# CPU's names of the step uniforms) that the film generation and the solver read.
known=(
  "cpu-reference/model/film_generation.cpp -> cpu-reference/stages/stages.h"
  "cpu-reference/solver/energy_budget.h -> cpu-reference/stages/stages.h"
  "cpu-reference/solver/implicit_euler.h -> cpu-reference/stages/stages.h"
)

declare -A header
while read -r path; do
  name=${path##*/}
  if [ -n "${header[$name]:-}" ]; then header[$name]=several; else header[$name]=$path; fi
done < <(git ls-files '*.h' '*.glsl')

up=0
while read -r file; do
  from=$(rank "$file")
  [ "$from" = 0 ] && continue
  while read -r included; do
    target=${header[${included##*/}]:-}
    [ -f "${file%/*}/$included" ] && target="${file%/*}/$included"
    { [ -z "$target" ] || [ "$target" = several ]; } && continue
    if [[ "$included" != */* && "$file" != kernels/* ]]; then
      echo "an include without its folder: $file -> \"$included\" (\"${target#cpu-reference/}\")"
      up=$((up + 1))
      continue
    fi
    [ "$(rank "$target")" -le "$from" ] && continue
    arrow="$file -> $target"
    printf '%s\n' "${known[@]}" | grep -qxF "$arrow" && continue
    echo "runs back up a layer: $arrow"
    up=$((up + 1))
  done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$file")
done < <(git ls-files '*.cpp' '*.h' '*.comp' '*.glsl' '*.vert' '*.frag')

if [ "$up" -gt 0 ]; then
  echo "check-layers: $up includes run back up a layer or name no folder (docs/architecture.md \"Layers\")"
  exit 1
fi
echo "check-layers: no include runs back up a layer (${#known[@]} known inside cpu-reference/)"
