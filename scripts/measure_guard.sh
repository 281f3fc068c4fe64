#!/usr/bin/env bash
# Avoid Self-Intersections against the plain run on the closed meshes of ../shared/meshes (issue #26's
# criteria; docs/performance.md#avoiding-self-intersections): Cube and Tetrahedron at lambda 4, 10 and
# 20, each until reldV < 1e-3 (at most 400 steps), with and without the guard. One line per run:
#   mesh style lambda guard share steps pairs_in->out held_max ms_per_step
#
# usage: scripts/measure_guard.sh [BUILD_DIR] [MESH ...]     (default: build/, every closed shared mesh)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$repo/build}"; shift || true
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then  # the closed ones, smallest first
  meshes=(small/cube_libigl_8.obj small/cube_odedstein_26.obj small/cube_gaussstylization_728.obj
          bunny/bunny_npm_1839.obj small/spot_triangulated_2930.obj bunny/bunny_odedstein_3301.obj
          bunny/bunny_cubicstylization_6172.obj armadillo/armadillo_odedstein_14587.obj
          bunny/bunny_watertight_34834.obj bunny/bun_zipper_35947.obj armadillo/armadillo_libigl_43243.obj)
fi
for mesh in "${meshes[@]}"; do
  for style in cube tetrahedron; do
    for lambda in 4 10 20; do
      for guard in off on; do
        flag=(); [ "$guard" = on ] && flag=(--avoid-self-intersections)
        out="$("$build/gauss_bench" "$repo/../shared/meshes/$mesh" --style "$style" --lambda "$lambda" \
               --until 1e-3 --steps 400 "${flag[@]}" 2>&1 || true)"
        field() { sed -n "s/^$1: //p" <<< "$out" | tail -1; }
        steps="$(field steps_to_converge)"; ms="$(field ms_to_converge)"
        echo "$mesh $style $lambda $guard $(field axis_share_10deg | sed 's/.*-> //') steps=[$steps]" \
             "pairs=$(field intersecting_pairs | tr -d ' ') held_max=$(field step_held_vertices_max) ms=[$ms]"
      done
    done
  done
done
