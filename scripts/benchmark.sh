#!/usr/bin/env bash
# Runs gauss_bench on the reference meshes of docs/performance.md (the bunny and the armadillo) with 2 threads and prints a Markdown table, one row
# per mesh and method: the Gauss method (cube style, lambda 4, sigma 4, 1 ADMM round) and the cubic
# method (cube, its default lambda 0.2). Per row: the medians of a 50-step run, then runs until the
# default tolerance (reldV < 1e-3, at most 2000 steps), plain and accelerated (--acceleration off /
# on, back to back): the steps and milliseconds that took and the share of faces within 10 degrees of
# a cube normal they ended at.
# Needs ../shared/meshes and a built build/.
# Measure on an otherwise idle machine: parallel loops suffer badly from competing processes.
set -euo pipefail
cd "$(dirname "$0")/.."
meshes=("${@:-../shared/meshes/bunny/bun_zipper_35947.obj ../shared/meshes/armadillo/armadillo_libigl_43243.obj}")
echo "| mesh | method, lambda | vertices | faces | set-up (ms) | step median (ms) | faces / rotations / ADMM / rhs / solve (ms) | share within 10° | steps to converge (plain / accelerated) | ms to converge (plain / accelerated) | share converged (plain / accelerated) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for mesh in ${meshes[@]}; do
  for method in gauss cubic; do
    if [ "$method" = gauss ]; then
      common=(--method gauss --style cube --lambda 4 --sigma 4 --admm 1 --threads 2)
    else
      common=(--method cubic --style cube --threads 2)
    fi
    out=$(./build/gauss_bench "$mesh" "${common[@]}" --steps 50)
    plain=$(./build/gauss_bench "$mesh" "${common[@]}" --until 1e-3 --steps 2000 --acceleration off)
    fast=$(./build/gauss_bench "$mesh" "${common[@]}" --until 1e-3 --steps 2000 --acceleration on)
    get() { echo "$out" | sed -n "s/^$1: //p"; }
    get_until() { echo "$plain" | sed -n "s/^$1: //p" | sed 's/.*-> //'; echo " / "; echo "$fast" | sed -n "s/^$1: //p" | sed 's/.*-> //'; }
    counts=$(echo "$out" | sed -n 's/^mesh: .*(\([0-9]*\) vertices, \([0-9]*\) faces)/\1 | \2/p')
    echo "| $(basename "$mesh") | $method $(get lambda) | $counts | $(get setup_ms) | $(get step_ms_median) | $(get phase_faces_ms_median) / $(get phase_rotations_ms_median) / $(get phase_admm_ms_median) / $(get phase_rhs_ms_median) / $(get phase_solve_ms_median) | $(get axis_share_10deg) | $(get_until steps_to_converge | tr -d '\n') | $(get_until ms_to_converge | tr -d '\n') | $(get_until axis_share_10deg | tr -d '\n') |"
  done
done
