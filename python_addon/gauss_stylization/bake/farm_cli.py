"""The farm's command line (docs/baking.md, "On a render farm"): a chunk of an animation bake, the
chunks merged, a batch of files stylized. It ships inside the add-on, since workers have the
add-on, not the repository:

    blender -b FILE.blend --python-exit-code 1 -P <add-on>/bake/farm_cli.py -- bake --object NAME --frames A-B --out chunk.pc2
    blender -b --python-exit-code 1 -P <add-on>/bake/farm_cli.py -- merge chunk_*.pc2 --out NAME.pc2
    blender -b --python-exit-code 1 -P <add-on>/bake/farm_cli.py -- batch FILE... --preset PRESET.json --out-dir DIR

and on Blender 4.2+, with the add-on enabled, the same as ``blender --command gauss_bake ...``
(bpy.utils.register_cli_command; there the .blend is given as ``--blend FILE.blend``).

Run as a script it finds the add-on package it belongs to, wherever Blender installed it (a classic
add-on, a 4.2+ extension as bl_ext.<repository>.<name>, or a plain folder), loads and registers it if
needed, and hands over to that package's copy of this module. Exit status: 0 done, 1 an error (its
message on stderr), 3 a batch that skipped files (listed).
"""

import argparse
import os
import sys

COMMAND = "gauss_bake"
EXIT_ERROR = 1
EXIT_SKIPPED = 3


def parser():
    main = argparse.ArgumentParser(prog=COMMAND, description="Gauss Stylization farm jobs (docs/baking.md)")
    main.add_argument("--blend", help="the .blend to open first (blender --command, where no file is given)")
    jobs = main.add_subparsers(dest="job", required=True)
    bake = jobs.add_parser("bake", help="bake frames A-B of an object to a .pc2 chunk, with the .blend's settings")
    bake.add_argument("--object", required=True, help="the mesh object's name")
    bake.add_argument("--frames", required=True, help="A-B, both included")
    bake.add_argument("--out", required=True, help="the .pc2 file to write")
    bake.add_argument("--blend", dest="blend_file", help=argparse.SUPPRESS)
    merge = jobs.add_parser("merge", help="join chunks into the .pc2 one bake of their frames writes")
    merge.add_argument("chunks", nargs="+", help=".pc2 chunks (any order; a glob is expanded)")
    merge.add_argument("--out", required=True, help="the .pc2 file to write")
    merge.add_argument("--frames", help="A-B: the frames the chunks must cover, no more, no less")
    batch = jobs.add_parser("batch", help="stylize .obj/.blend files with a saved preset, one output each")
    batch.add_argument("files", nargs="+", help=".obj and .blend files")
    batch.add_argument("--preset", required=True, help="settings JSON (settings_io.to_json)")
    batch.add_argument("--out-dir", required=True, help="folder for the outputs ('<name>_gauss.obj/.blend')")
    batch.add_argument("--object", help="in .blend files, stylize only this object (default: every visible mesh)")
    batch.add_argument("--blend", dest="blend_file", help=argparse.SUPPRESS)
    return main


def main(argv):
    """Run one job; returns the exit status. Errors are printed, never raised."""
    import bpy

    from ..errors import NativeModuleError, SettingsError
    from . import batch, farm
    try:
        args = parser().parse_args(argv)
    except SystemExit as exc:  # argparse printed the usage or the help
        return EXIT_ERROR if exc.code else 0
    try:
        blend = args.blend or getattr(args, "blend_file", None)
        if blend:
            if not os.path.isfile(blend):
                raise SettingsError("No .blend file %s" % blend)
            bpy.ops.wm.open_mainfile(filepath=os.path.abspath(blend))
        if args.job == "bake":
            first, last = farm.parse_frames(args.frames)
            farm.bake_chunk(args.object, first, last, args.out)
        elif args.job == "merge":
            frames = farm.parse_frames(args.frames) if args.frames else None
            farm.merge_chunks(args.chunks, args.out, frames)
        else:
            _outputs, skipped = batch.run(args.files, args.preset, args.out_dir, args.object)
            return EXIT_SKIPPED if skipped else 0
    except (SettingsError, NativeModuleError, OSError, ValueError, RuntimeError) as exc:
        print("%s: error: %s" % (COMMAND, exc), file=sys.stderr, flush=True)
        return EXIT_ERROR
    return 0


_handles = []


def register():
    """blender --command gauss_bake (Blender 4.2+)."""
    import bpy
    if hasattr(bpy.utils, "register_cli_command") and not _handles:
        _handles.append(bpy.utils.register_cli_command(COMMAND, main))


def unregister():
    import bpy
    while _handles:
        bpy.utils.unregister_cli_command(_handles.pop())


# -- run as a script (blender -P): find and load the add-on this file is part of -----------------

def _addon_package():
    """The add-on package holding this file, loaded and registered."""
    import importlib

    import addon_utils
    import bpy
    folder = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    init = os.path.normcase(os.path.realpath(os.path.join(folder, "__init__.py")))

    def is_ours(module):
        path = getattr(module, "__file__", None)
        return bool(path) and os.path.normcase(os.path.realpath(path)) == init

    # Loaded already: enabled in the preferences (classic or bl_ext.<repository>.<name>), or by a script.
    package = next((module for module in list(sys.modules.values()) if is_ours(module)), None)
    how = "loaded"
    if package is None:
        # Installed where Blender looks for add-ons or extensions, but not enabled: enable it by its name.
        known = next((module for module in addon_utils.modules(refresh=True) if is_ours(module)), None)
        if known is not None:
            package, how = addon_utils.enable(known.__name__, default_set=False, persistent=False), "enabled"
    if package is None:
        # A plain folder (a build tree, a copy on a network share): import it from its parent.
        sys.path.insert(0, os.path.dirname(folder))
        package, how = importlib.import_module(os.path.basename(folder)), "imported"
    print("%s: add-on '%s' %s from %s" % (COMMAND, package.__name__, how, folder), flush=True)
    if not hasattr(bpy.types.Object, "gauss_stylization"):
        package.register()
    return package


def _script_args():
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


if __name__ == "__main__":
    _own = __import__(_addon_package().__name__ + ".bake.farm_cli", fromlist=["main"])
    sys.exit(_own.main(_script_args()))
