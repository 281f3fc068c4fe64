"""Install an extension zip the way Blender 4.2+ does, and say where the add-on went.

    python install_extension.py EXTENSION_ZIP    (run by a Python that has `bpy`, Blender as a module)

Installs and enables EXTENSION_ZIP with Blender's own operator (Preferences > Get Extensions >
Install from Disk: bpy.ops.extensions.package_install_files) into the "user_default" repository of the
Blender user folder that the BLENDER_USER_* environment variables name (scripts/test_blender_versions.sh
points them at a throw-away folder). Enabling it makes Blender install the wheels the manifest lists
into its extensions' site-packages, which every later Blender session of that user folder puts on
sys.path. Prints the folder holding the installed gauss_stylization package (last line); exits
non-zero with the reason if Blender did not install the add-on or its gauss_core wheel.
"""

import importlib.util
import os
import sys

import bpy

from blender_process import run_and_exit

PACKAGE = "gauss_stylization"
REPOSITORY = "user_default"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    archive = os.path.abspath(sys.argv[1])
    result = bpy.ops.extensions.package_install_files(filepath=archive, repo=REPOSITORY, enable_on_install=True)
    folder = bpy.utils.user_resource('EXTENSIONS', path=REPOSITORY)
    if result != {'FINISHED'} or not os.path.isfile(os.path.join(folder, PACKAGE, "__init__.py")):
        sys.exit("Blender %s did not install %s (%s; %s)" % (bpy.app.version_string, archive, result, folder))
    if importlib.util.find_spec("gauss_core") is None:
        sys.exit("Blender %s installed %s but not its gauss_core wheel" % (bpy.app.version_string, archive))
    print(folder)


run_and_exit(main)
