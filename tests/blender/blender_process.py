"""Run a Python script in a second, headless Blender: the one running the tests.

    blender_command(script, args, blend=None, factory_startup=False) -> argv for subprocess.run

Inside the Blender program (`blender -b`) that is the same binary with -b, --python-expr and
--python-exit-code 1. Inside Blender as a Python module (a `bpy` wheel) there is no Blender binary
(bpy.app.binary_path is empty), so it is the same Python importing bpy. Either way the script sees its
``args`` at the end of sys.argv (after "--" in Blender's), runs with ``blend`` opened when given
(else the startup scene, or the factory one with ``factory_startup``), and an exception in it makes
the process exit non-zero (see exit_code).
"""

import os
import sys
import traceback

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))

# sys.argv: [-c, HERE, BLEND, FACTORY (0/1), SCRIPT, args...]
_MODULE_BOOT = """
import sys
sys.path.insert(0, sys.argv[1])
import bpy
from blender_process import run_and_exit
blend, factory, script = sys.argv[2], sys.argv[3] == "1", sys.argv[4]
sys.argv = [sys.argv[0], "--"] + sys.argv[5:]
if factory:
    bpy.ops.wm.read_factory_settings()
if blend:
    bpy.ops.wm.open_mainfile(filepath=blend)
run_and_exit(lambda: exec(compile(script, "<python-expr>", "exec"), {"__name__": "__main__"}))
"""


def exit_now(status):
    """End the process with ``status`` without Python's exit. Blender as a Python module crashes (bpy
    4.2: SIGSEGV) or hangs (bpy 4.5) at interpreter exit while a Python function is in
    bpy.app.handlers, whatever registered it (measured with one no-op load_post handler and nothing
    else), so a script run in it ends here once its result is out."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)


def run_and_exit(function):
    """Call ``function``; exit 0, or print the traceback and exit 1 if it raised (exit_now)."""
    try:
        function()
    except BaseException:  # noqa: BLE001 - any failure is the script's result
        traceback.print_exc()
        exit_now(1)
    exit_now(0)


def blender_command(script, args=(), blend=None, factory_startup=False, exit_code=True):
    """exit_code=False: the Blender program exits with 0 even when the script raised (and then
    prints no copy of the script); a Python always exits non-zero then."""
    if bpy.app.binary_path:
        return ([bpy.app.binary_path, "-b"] + ([blend] if blend else [])
                + (["--factory-startup"] if factory_startup else [])
                + (["--python-exit-code", "1"] if exit_code else [])
                + ["--python-expr", script, "--", *args])
    return [sys.executable, "-c", _MODULE_BOOT, HERE, blend or "", "1" if factory_startup else "0", script, *args]
