#!/usr/bin/env python3
"""The install check of scripts/package_addon.py --verify-install: a classic add-on zip is installed
into a throw-away Blender user configuration (BLENDER_USER_CONFIG / BLENDER_USER_SCRIPTS in a temporary
folder, so the machine's own configuration is not touched), enabled, and stylizes a sphere, using
`blender` from PATH (or $BLENDER).

    verify_install(zip_path, python, package)   python: "X.Y" the module was built for; package: the
                                                add-on's folder name. Prints the check's result lines;
                                                raises InstallCheckFailed with the reason if it fails.
"""

import os
import re
import subprocess
import sys
import tempfile


class InstallCheckFailed(RuntimeError):
    """The zip did not install, enable or stylize; the message says why."""


VERIFY_SCRIPT = r'''
import sys, bpy, addon_utils
zip_path = sys.argv[sys.argv.index("--") + 1]
print("blender python %d.%d" % sys.version_info[:2])
bpy.ops.preferences.addon_install(filepath=zip_path)
bpy.ops.preferences.addon_enable(module="gauss_stylization")
loaded, enabled = addon_utils.check("gauss_stylization")
assert loaded and enabled, "add-on not enabled"
import gauss_stylization
print("installed at", gauss_stylization.__file__)
gauss_stylization.native.core()  # raises the add-on's readable error if the .so does not load
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=3)
result = bpy.ops.object.gauss_stylize(iterations=20)
assert result == {"FINISHED"}, result
print("VERIFY OK: installed, enabled and stylized with", gauss_stylization.bl_info["name"],
      gauss_stylization.bl_info["version"])
'''


def path_without_this_python():
    """PATH without the folder of the interpreter running this script, unless it is the system's.

    Debian's Blender runs the system Python but takes its prefix from the first `python3` on
    PATH; run from e.g. a pyenv Python, it would get that Python's library (without numpy).
    """
    own = os.path.dirname(os.path.realpath(sys.executable))
    parts = os.environ.get("PATH", "").split(os.pathsep)
    if own in ("/usr/bin", "/bin"):
        return os.pathsep.join(parts)
    return os.pathsep.join(p for p in parts if os.path.realpath(p) != own)


def verify_install(zip_path, python, package):
    """Raises InstallCheckFailed unless `zip_path` installs, enables and stylizes in `blender -b`."""
    blender = os.environ.get("BLENDER", "blender")
    with tempfile.TemporaryDirectory(prefix="gauss_verify_") as home:
        env = dict(os.environ,
                   BLENDER_USER_CONFIG=os.path.join(home, "config"),
                   BLENDER_USER_SCRIPTS=os.path.join(home, "scripts"),
                   PATH=path_without_this_python())
        script = os.path.join(home, "verify.py")
        with open(script, "w", encoding="utf-8") as handle:
            handle.write(VERIFY_SCRIPT)
        command = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "-P", script, "--", zip_path]
        result = subprocess.run(command, env=env, capture_output=True, text=True)
        installed = os.path.join(home, "scripts", "addons", package, "__init__.py")
        ok = result.returncode == 0 and "VERIFY OK" in result.stdout and os.path.isfile(installed)
        print("\n".join(line for line in result.stdout.splitlines()
                        if line.startswith(("blender python", "installed at", "VERIFY"))))
        if not ok:
            sys.stderr.write(result.stdout[-3000:] + result.stderr[-3000:])
            blender_python = re.search(r"^blender python (\S+)$", result.stdout, re.M)
            if blender_python and blender_python.group(1) != python:
                raise InstallCheckFailed(
                    "this Blender runs Python %s but the module was built for Python %s: rebuild with "
                    "cmake -DPython_EXECUTABLE=<a python%s> (see README)"
                    % (blender_python.group(1), python, blender_python.group(1)))
            raise InstallCheckFailed("install check failed (blender exit code %d)" % result.returncode)
