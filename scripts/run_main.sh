#!/usr/bin/env bash
# The main job: install what is missing, build, stylize the default scene headless in Blender and
# write a .blend and a rendered PNG to OUT_DIR (default: out/).
set -euo pipefail
cd "$(dirname "$0")/.."
out="$(realpath -m "${1:-out}")"
bash scripts/install_deps.sh
bash scripts/build.sh build --main  # the module and the add-on; scripts/run_tests.sh builds the tests
mkdir -p "$out"
blender -b --factory-startup --python-exit-code 1 -P blender_scenes/default_scene.py -- build "$out"
echo "== done: $out"
ls -l "$out"
