#!/usr/bin/env python3
"""Package the add-on for installation in Blender.

    python3 scripts/package_addon.py BUILD_DIR OUT_DIR [--verify-install]

BUILD_DIR is a build tree of scripts/build.sh (it holds the compiled solver module,
BUILD_DIR/addon/gauss_stylization/gauss_core*.so). Writes to OUT_DIR:

  gauss_stylization-VERSION-addon-TAG.zip      legacy add-on: Preferences > Add-ons > Install...;
      one top-level folder gauss_stylization/
  gauss_stylization-VERSION-extension-TAG.zip  extension (Blender 4.2+): Preferences > Get
      Extensions > Install from Disk...; blender_manifest.toml at the root; only for a Python
      that some Blender 4.2+ runs (not for 3.10)

TAG names the Python the module was built for (e.g. cp311-linux_x86_64): the zip only
works in a Blender that runs that Python version. The add-on's Python files come from
python_addon/gauss_stylization/ (never stale), the .so and core_facts.json (the solver's
defaults, limits and presets, which the add-on reads when the .so cannot load) from the build. The zips are
reproducible (sorted entries, fixed timestamps).

--verify-install installs the legacy zip into a throw-away Blender user configuration
(BLENDER_USER_CONFIG / BLENDER_USER_SCRIPTS in a temporary folder, so the machine's own
configuration is not touched), enables it and stylizes a sphere with it, using `blender`
from PATH (or $BLENDER).

Which Blender releases run which Python is written once, in BLENDER_FOR_PYTHON below: the
manifest's blender_version_min/max and the README.txt in each zip (which Blender loads it,
the glibc it needs, which zip the other Blenders need) derive from it.
"""

import argparse
import ast
import glob
import os
import re
import subprocess
import sys
import tempfile
import tomllib
import zipfile

import module_reach  # scripts/module_reach.py: what the module needs from the system

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCE = os.path.join(REPO, "python_addon", "gauss_stylization")
MANIFEST_TEMPLATE = os.path.join(REPO, "packaging", "blender_manifest.toml.in")
PACKAGE = "gauss_stylization"
ZIP_DATE = (1980, 1, 1, 0, 0, 0)
# CPython extension suffix, e.g. gauss_core.cpython-311-x86_64-linux-gnu.so
SO_PATTERN = re.compile(r"^gauss_core\.cpython-(?P<major>\d)(?P<minor>\d+)-(?P<platform>[^.]+)\.so$")

# Which Blender runs which Python (the module only loads in the Python it was built for): official
# blender.org releases, first and last inclusive, with the numpy they bundle; a Linux distribution's
# blender package runs the system Python instead ("also"). The one place these facts are written.
BLENDER_FOR_PYTHON = {
    "3.10": {"official": ((3, 1), (4, 0)), "numpy": "1.x", "also": ()},
    "3.11": {"official": ((4, 1), (5, 0)), "numpy": "1.x", "also": ("Debian 12's blender package (3.4.1)",)},
    "3.13": {"official": ((5, 1), (5, 1)), "numpy": "2.x", "also": ()},
}
EXTENSIONS_SINCE = (4, 2)  # the first Blender that installs extensions (blender_manifest.toml)


def fail(message):
    sys.exit("package_addon.py: " + message)


def addon_info():
    """The add-on's bl_info (read without importing bpy)."""
    with open(os.path.join(SOURCE, "__init__.py"), encoding="utf-8") as handle:
        tree = ast.parse(handle.read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "bl_info" for t in node.targets):
            return ast.literal_eval(node.value)
    fail("no bl_info in %s" % SOURCE)


def release(version):
    return "%d.%d" % version[:2]


def releases(first, last):
    return release(first) if first == last else "%s to %s" % (release(first), release(last))


def blender_ranges(python, addon_min):
    """Official Blender releases that load a module built for `python`, as (first, last) pairs of
    (major, minor): for the classic zip, and for the extension zip (None: no extension Blender)."""
    row = BLENDER_FOR_PYTHON.get(python)
    if row is None:
        fail("the module was built for Python %s, which no Blender release runs (Blender runs %s): build "
             "it against Blender's Python (README, \"Which Blender can load this build\")"
             % (python, ", ".join(BLENDER_FOR_PYTHON)))
    first, last = row["official"]
    classic = (max(first, addon_min), last)
    extension = (max(first, EXTENSIONS_SINCE), last) if last >= EXTENSIONS_SINCE else None
    return classic, extension


def native_module(build_dir):
    """The one compiled solver module of the build, and its Python/platform tags."""
    staged = os.path.join(build_dir, "addon", PACKAGE)
    found = sorted(glob.glob(os.path.join(staged, "gauss_core*.so")))
    if not found:
        fail("no gauss_core*.so in %s: build first (bash scripts/build.sh %s)" % (staged, build_dir))
    if len(found) > 1:
        fail("several solver modules in %s (%s): remove the stale ones or use a fresh build directory"
             % (staged, ", ".join(os.path.basename(p) for p in found)))
    match = SO_PATTERN.match(os.path.basename(found[0]))
    if match is None:
        fail("unexpected module name %s (expected gauss_core.cpython-XY-PLATFORM.so)" % found[0])
    python = "%s.%s" % (match["major"], match["minor"])
    if match["platform"] != "x86_64-linux-gnu":
        fail("built for %s; the manifest only declares linux-x64" % match["platform"])
    return found[0], python, "cp%s%s-linux_x86_64" % (match["major"], match["minor"])


def module_glibc(so_path):
    """The oldest glibc the module loads on, e.g. "2.17", as readelf shows it (scripts/module_reach.py);
    warns about anything beyond the allowance the README documents."""
    try:
        newest = module_reach.newest_glibc(so_path)
        beyond = module_reach.problems(so_path)
    except RuntimeError as exc:
        fail("cannot inspect %s: %s" % (so_path, exc))
    for line in beyond:
        print("package_addon.py: warning: the module %s; the zips' README.txt names what it needs" % line)
    return ".".join(map(str, newest)) if newest else "(any version)"


def addon_files(so_path):
    """(path on disk, name inside the package) of everything that ships, sorted."""
    files = []
    for name in sorted(os.listdir(SOURCE)):
        if name.endswith(".py"):
            files.append((os.path.join(SOURCE, name), name))
    if not any(name == "__init__.py" for _, name in files):
        fail("no __init__.py in %s" % SOURCE)
    facts = os.path.join(os.path.dirname(so_path), "core_facts.json")
    if not os.path.isfile(facts):
        fail("no core_facts.json next to %s: rebuild (bash scripts/build.sh)" % so_path)
    files += [(facts, "core_facts.json"), (so_path, os.path.basename(so_path))]
    return sorted(files, key=lambda entry: entry[1])


def write_zip(path, entries):
    """entries: (name in zip, bytes, unix mode). Deterministic output."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as archive:
        for name, data, mode in sorted(entries):
            info = zipfile.ZipInfo(name, date_time=ZIP_DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = (0o100000 | mode) << 16
            archive.writestr(info, data)


def read(path):
    with open(path, "rb") as handle:
        return handle.read()


def mode_of(name):
    return 0o755 if name.endswith(".so") else 0o644


def manifest_text(version, python, extension_range):
    with open(MANIFEST_TEMPLATE, encoding="utf-8") as handle:
        text = handle.read()
    first, last = extension_range
    # blender_version_max is the first release the extension does NOT support.
    for placeholder, value in (("@VERSION@", version), ("@PYTHON@", python),
                               ("@BLENDER_MIN@", "%d.%d.0" % first),
                               ("@BLENDER_MAX@", "%d.%d.0" % (last[0], last[1] + 1))):
        text = text.replace(placeholder, value)
    if re.search(r"@[A-Z_]+@", text):
        fail("unfilled placeholder in %s" % MANIFEST_TEMPLATE)
    manifest = tomllib.loads(text)  # must parse, and follow Blender's rules for these fields
    for key in ("schema_version", "id", "version", "name", "tagline", "maintainer", "type",
                "blender_version_min", "blender_version_max", "license"):
        if key not in manifest:
            fail("manifest lacks %r" % key)
    tagline = manifest["tagline"]
    if len(tagline) > 64 or not (tagline[-1].isalnum() or tagline[-1] in ")]}"):
        fail("manifest tagline must be at most 64 characters and not end with punctuation")
    if manifest["id"] != PACKAGE:
        fail("manifest id must be %r" % PACKAGE)
    return text


def readme_text(kind, version, so_name, python, blender, glibc, addon_min):
    """README.txt of a zip: which Blender loads it, what it needs, which zip the other Blenders need."""
    row = BLENDER_FOR_PYTHON[python]
    loads = ["official Blender %s (Python %s, numpy %s)" % (releases(*blender), python, row["numpy"])]
    if kind == "add-on":
        loads += list(row["also"])
    others = ["  official Blender %s%s (Python %s): the add-on zip whose name ends in -cp%s-linux_x86_64.zip"
              % (releases(*blender_ranges(other, addon_min)[0]), "".join(", " + a for a in entry["also"]),
                 other, other.replace(".", ""))
              for other, entry in BLENDER_FOR_PYTHON.items() if other != python]
    install = ("Edit > Preferences > Add-ons > Install... (in Blender 4.2+: Install from Disk... in the "
               "drop-down menu at the top right of the Add-ons section), then enable Mesh: Gauss Stylization."
               if kind == "add-on" else
               "Edit > Preferences > Get Extensions, the drop-down menu at the top right, Install from Disk...")
    return "\n".join([
        "Gauss Stylization %s, %s for Blender" % (version, kind),
        "",
        "Solver module: %s, built for Python %s, Linux x86-64." % (so_name, python),
        "It needs glibc %s or newer and no other system library." % glibc,
        "",
        "Loads in: " + "; ".join(loads) + ".",
        "Other Blenders run another Python and cannot load this module; they need:",
        *others,
        "or a module built for their Python (source README, \"Which Blender can load this build\").",
        "",
        "Install: " + install,
        "",
    ])


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


def verify_install(zip_path, python):
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
        installed = os.path.join(home, "scripts", "addons", PACKAGE, "__init__.py")
        ok = result.returncode == 0 and "VERIFY OK" in result.stdout and os.path.isfile(installed)
        print("\n".join(line for line in result.stdout.splitlines()
                        if line.startswith(("blender python", "installed at", "VERIFY"))))
        if not ok:
            sys.stderr.write(result.stdout[-3000:] + result.stderr[-3000:])
            blender_python = re.search(r"^blender python (\S+)$", result.stdout, re.M)
            if blender_python and blender_python.group(1) != python:
                fail("this Blender runs Python %s but the module was built for Python %s: rebuild with "
                     "cmake -DPython_EXECUTABLE=<a python%s> (see README)"
                     % (blender_python.group(1), python, blender_python.group(1)))
            fail("install check failed (blender exit code %d)" % result.returncode)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("out_dir")
    parser.add_argument("--verify-install", action="store_true",
                        help="install the classic zip into a temporary Blender user config and use it")
    args = parser.parse_args()
    build_dir, out_dir = os.path.abspath(args.build_dir), os.path.abspath(args.out_dir)
    info = addon_info()
    version = ".".join(str(part) for part in info["version"])
    so_path, python, tag = native_module(build_dir)
    addon_min = tuple(info["blender"][:2])
    classic_range, extension_range = blender_ranges(python, addon_min)
    glibc = module_glibc(so_path)
    packaged = [(name, read(path), mode_of(name)) for path, name in addon_files(so_path)]
    so_name = os.path.basename(so_path)
    os.makedirs(out_dir, exist_ok=True)
    print("add-on %s, solver module for Python %s (%s), needs glibc %s" % (version, python, so_name, glibc))

    classic = os.path.join(out_dir, "%s-%s-addon-%s.zip" % (PACKAGE, version, tag))
    readme = readme_text("add-on", version, so_name, python, classic_range, glibc, addon_min)
    write_zip(classic, [("%s/%s" % (PACKAGE, name), data, mode)
                        for name, data, mode in packaged + [("README.txt", readme.encode("utf-8"), 0o644)]])
    print("classic add-on zip (official Blender %s%s): %s"
          % (releases(*classic_range), "".join(", " + a for a in BLENDER_FOR_PYTHON[python]["also"]), classic))

    if extension_range is None:
        print("no extension zip: Blender %s and later run another Python than %s"
              % (release(EXTENSIONS_SINCE), python))
    else:
        extension = os.path.join(out_dir, "%s-%s-extension-%s.zip" % (PACKAGE, version, tag))
        readme = readme_text("extension", version, so_name, python, extension_range, glibc, addon_min)
        manifest = manifest_text(version, python, extension_range)
        write_zip(extension, packaged + [("README.txt", readme.encode("utf-8"), 0o644),
                                         ("blender_manifest.toml", manifest.encode("utf-8"), 0o644)])
        print("extension zip (Blender %s): %s" % (releases(*extension_range), extension))
    if args.verify_install:
        verify_install(classic, python)


if __name__ == "__main__":
    main()
