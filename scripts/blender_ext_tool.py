#!/usr/bin/env python3
"""Blender's own extension tooling, blender_ext.py, as Blender 4.2+ runs it for
`blender --command extension build` and `extension validate`; it runs with plain Python >= 3.11.

    python3 scripts/blender_ext_tool.py            prints the path of blender_ext.py (fetching it first)

Taken from the bpy wheel pinned below (PyPI's Blender-as-a-module carries Blender's scripts): the
first use downloads the wheel with pip into a temporary folder, keeps only blender_ext.py in
${XDG_CACHE_HOME:-~/.cache}/gauss_stylization/blender_ext-bpy-<version>/ and deletes the wheel.
scripts/package_addon.py builds and validates the extension zips with it.
"""

import importlib.util
import os
import subprocess
import sys
import tempfile
import zipfile

# The newest bpy for Python 3.11 when this was written; its validator knows the manifest rules of
# every Blender from 4.2 on (platforms, wheels, permissions).
BPY_VERSION = "5.0.1"
BPY_PYTHON = "3.11"
MEMBER_SUFFIX = "/scripts/addons_core/bl_pkg/cli/blender_ext.py"

CACHE = os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"),
                     "gauss_stylization", "blender_ext-bpy-%s" % BPY_VERSION)


def path():
    """blender_ext.py's path, fetched on first use; RuntimeError with the reason if that fails."""
    target = os.path.join(CACHE, "blender_ext.py")
    if os.path.isfile(target):
        return target
    with tempfile.TemporaryDirectory(prefix="gauss_bpy_") as download:
        command = [sys.executable, "-m", "pip", "download", "-q", "--disable-pip-version-check", "--no-deps",
                   "--only-binary=:all:", "--python-version", BPY_PYTHON, "--platform",
                   "manylinux_2_28_x86_64", "-d", download, "bpy==%s" % BPY_VERSION]
        result = subprocess.run(command, capture_output=True, text=True)
        wheels = [name for name in os.listdir(download) if name.endswith(".whl")]
        if result.returncode != 0 or len(wheels) != 1:
            raise RuntimeError("cannot download bpy==%s to take Blender's extension tool from it: %s"
                               % (BPY_VERSION, result.stderr.strip()[-2000:]))
        with zipfile.ZipFile(os.path.join(download, wheels[0])) as wheel:
            members = [name for name in wheel.namelist() if name.endswith(MEMBER_SUFFIX)]
            if len(members) != 1:
                raise RuntimeError("bpy==%s holds %d copies of blender_ext.py" % (BPY_VERSION, len(members)))
            os.makedirs(CACHE, exist_ok=True)
            partial = target + ".partial"
            with open(partial, "wb") as handle:
                handle.write(wheel.read(members[0]))
            os.replace(partial, target)
    return target


def run(*arguments):
    """Runs blender_ext.py with these arguments; (exit code, its output)."""
    result = subprocess.run([sys.executable, path(), *arguments], capture_output=True, text=True)
    return result.returncode, (result.stdout + result.stderr).strip()


def module():
    """blender_ext.py imported, for its own rules (e.g. blender_platforms_from_wheel_platform)."""
    spec = importlib.util.spec_from_file_location("blender_ext", path())
    loaded = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(loaded)
    return loaded


if __name__ == "__main__":
    try:
        print(path())
    except RuntimeError as exc:
        sys.exit("blender_ext_tool.py: %s" % exc)
