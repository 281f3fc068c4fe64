"""Runs every code snippet of docs/scripting.md and docs/baking.md in Blender as a Python module (a `bpy`
wheel) where the add-on is installed as an extension, as an artist's script would meet it.

    python doc_snippets.py EXTENSION_ZIP    (a Python with `bpy`; BLENDER_USER_* name a throw-away user
                                             folder: scripts/test_blender_versions.sh runs it)

Installs EXTENSION_ZIP the way the docs say, with the command line's operator (`blender --command
extension install-file -r user_default -e ZIP` runs bpy.ops.extensions.package_install_files), then
runs each document's snippets in order, the Python ones in one namespace, on a scene
the snippets assume: a subdivided Suzanne with the vertex groups "Feet", "Head" and "Tail", an object
"Low-poly example", saved as scene.blend (and shot.blend with the mesh called "Hero") so that `//`
paths resolve. A shell snippet runs as Blender would run it: `blender -b FILE --addons NAMES
--python-expr EXPR` opens FILE, enables each add-on by that name with addon_utils and runs EXPR;
`blender --command extension install-file ... ZIP` installs EXTENSION_ZIP. The one snippet it does
not run is the classic zip's install into a separate user folder (other environment variables, a
classic zip): `package_addon.py --verify-install` runs that one in Debian's Blender.
Prints one line per snippet, then "doc snippets: N passed, M failed"; exits non-zero if any failed.
"""

import os
import re
import shlex
import sys
import tempfile
import traceback

import bpy  # first: Blender as a module puts its scripts' modules (addon_utils) on sys.path on import
import addon_utils  # noqa: E402
import bmesh  # noqa: E402

from blender_process import exit_now  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOCS = ("docs/scripting.md", "docs/baking.md")
BLOCK = re.compile(r"^```(python|sh)\n(.*?)^```", re.M | re.S)
# Snippets run elsewhere, by what marks them: (marker, where they run instead).
NOT_HERE = (
    ("BLENDER_USER_CONFIG=$tmp/config", "the classic zip's install; package_addon.py --verify-install"),
    ("/path/to/repo/build/addon", "the add-on of a build tree, not an installed one; tests/blender runs it so"),
    ("bake/farm_cli.py -- ", "the farm command line; tests/blender/test_farm.py and tests/farm"),
    ("farm/slurm/submit.sh", "a Slurm cluster; tests/farm/test_slurm.py"),
    ("openjd run", "Open Job Description's runner; tests/farm/test_openjd.py"),
)


def snippets(path):
    with open(os.path.join(REPO, path), encoding="utf-8") as handle:
        text = handle.read()
    for match in BLOCK.finditer(text):
        yield text.count("\n", 0, match.start()) + 1, match.group(1), match.group(2)


def make_scene(folder):
    """Suzanne (subdivided once) with its groups and a low-poly example, saved as scene.blend and shot.blend."""
    bpy.ops.wm.read_homefile(use_empty=True)  # keeps the preferences: the extension stays enabled
    bm = bmesh.new()
    bmesh.ops.create_monkey(bm)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=1, use_grid_fill=True)
    mesh = bpy.data.meshes.new("Suzanne")
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new("Suzanne", mesh)
    bpy.context.scene.collection.objects.link(obj)
    heights = [v.co.z for v in mesh.vertices]
    depth = [v.co.y for v in mesh.vertices]
    for name, chosen in (("Feet", [i for i, z in enumerate(heights) if z < min(heights) + 0.15]),
                         ("Head", [i for i, z in enumerate(heights) if z > 0.2]),
                         ("Tail", [i for i, y in enumerate(depth) if y > max(depth) - 0.3])):
        obj.vertex_groups.new(name=name).add(chosen, 1.0, 'REPLACE')
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    example = bpy.data.meshes.new("Low-poly example")
    bm.to_mesh(example)
    bm.free()
    other = bpy.data.objects.new("Low-poly example", example)
    other.rotation_euler = (0.3, 0.2, 0.0)
    bpy.context.scene.collection.objects.link(other)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    scene = os.path.join(folder, "scene.blend")
    bpy.ops.wm.save_as_mainfile(filepath=scene)
    obj.name = "Hero"
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(folder, "shot.blend"))
    bpy.ops.wm.open_mainfile(filepath=scene)
    return scene


def install(archive, repo):
    result = bpy.ops.extensions.package_install_files(filepath=archive, repo=repo, enable_on_install=True)
    if result != {'FINISHED'}:
        raise RuntimeError("package_install_files: %s" % result)


def run_shell(code, folder, archive):
    """The snippet's blender command lines, as Blender runs them (see the module's docstring)."""
    for line in code.replace("\\\n", " ").splitlines():
        words = shlex.split(line)
        if not words or words[0] != "blender":
            raise RuntimeError("not a blender command: %s" % line)
        if words[1:4] == ["--command", "extension", "install-file"]:
            repo = words[words.index("-r") + 1]
            install(archive, repo)
            continue
        files = [w for w in words[1:] if w.endswith(".blend")]
        if files:
            bpy.ops.wm.open_mainfile(filepath=os.path.join(folder, files[0]))
        for name in words[words.index("--addons") + 1].split(",") if "--addons" in words else ():
            if addon_utils.enable(name, default_set=True) is None:
                raise RuntimeError("--addons %s: no add-on of that name" % name)
        if "--python-expr" in words:
            exec(compile(words[words.index("--python-expr") + 1], "<python-expr>", "exec"), {"__name__": "__main__"})


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    archive = os.path.abspath(sys.argv[1])
    passed, failed = 0, []
    install(archive, "user_default")  # what the command line's install-file does (docs/scripting.md)
    # One namespace for both documents: baking.md's snippets use `gauss` as scripting.md finds it.
    namespace = {"__name__": "__main__"}
    with tempfile.TemporaryDirectory(prefix="gauss_doc_snippets_") as folder:
        for doc in DOCS:
            make_scene(folder)
            for line, kind, code in snippets(doc):
                where = "%s:%d (%s)" % (doc, line, kind)
                elsewhere = [why for marker, why in NOT_HERE if marker in code]
                if elsewhere:
                    print("%s: not run here (%s)" % (where, elsewhere[0]))
                    continue
                try:
                    if kind == "python" and '"Hero"' in code and "Hero" not in bpy.data.objects:
                        bpy.ops.wm.open_mainfile(filepath=os.path.join(folder, "shot.blend"))  # the farm's shot
                    if kind == "python":
                        exec(compile(code, where, "exec"), namespace)
                    else:
                        run_shell(code, folder, archive)
                    passed += 1
                    print("%s: ok" % where)
                except Exception:
                    failed.append(where)
                    print("%s: FAILED\n%s" % (where, traceback.format_exc()))
    print("doc snippets: %d passed, %d failed" % (passed, len(failed)))
    return 1 if failed else 0


exit_now(main())
