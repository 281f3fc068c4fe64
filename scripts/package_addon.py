#!/usr/bin/env python3
"""Package the add-on for installation in Blender.

    python3 scripts/package_addon.py BUILD_DIR OUT_DIR [--wheels WHEEL...] [--verify-install]
    python3 scripts/package_addon.py --table     (the README's table of which Blender gets which zip)

BUILD_DIR is a build tree of scripts/build.sh: it holds core_facts.json (the solver's defaults,
limits and presets, which the add-on reads when the module cannot load) and the staged module
BUILD_DIR/addon/gauss_stylization/gauss_core*.so. The add-on's Python files come from
python_addon/gauss_stylization/ (never stale). Writes to OUT_DIR, printing one line per zip:

Without --wheels (the Blender tests' and the README's local build):
  gauss_stylization-VERSION-addon-cpXY-linux_x86_64.zip     classic add-on with BUILD_DIR's module:
      Preferences > Add-ons > Install...; one top-level folder gauss_stylization/

With --wheels WHEEL... (gauss_core wheels of scripts/build_wheel.sh or cibuildwheel, any Pythons and
platforms), for each Python among them:
  gauss_stylization-VERSION-extension-cpXY-PLATFORM.zip     extension (Blender 4.2+), one per platform
      (linux_x64, windows_x64, macos_arm64, macos_x64: those the wheels cover), made by Blender's own
      tooling (blender_ext.py build --split-platforms, scripts/blender_ext_tool.py) from a manifest
      that lists the wheels, the platforms and the files permission, then checked with Blender's
      validator (blender_ext.py validate). Preferences > Get Extensions > Install from Disk...
  gauss_stylization-VERSION-addon-cpXY-TAG.zip              classic add-on per wheel, the module
      taken out of the wheel (TAG: linux_x86_64, win_amd64, macosx_arm64, macosx_x86_64)

Which Blender releases run which Python is written once, in BLENDER_FOR_PYTHON below: the manifest's
blender_version_min/max, the README.txt in each zip (which Blender loads it, which zip the other
Blenders need) and the tests derive from it. A zip only works in a Blender that runs the Python its
module was built for.

--verify-install installs the linux classic zip for this Python into a throw-away Blender user
configuration (BLENDER_USER_CONFIG / BLENDER_USER_SCRIPTS in a temporary folder, so the machine's own
configuration is not touched), enables it and stylizes a sphere with it, using `blender` from PATH
(or $BLENDER).
"""

import argparse
import ast
import glob
import os
import re
import shutil
import sys
import tempfile
import tomllib
import zipfile

import binary_facts  # scripts/binary_facts.py: what a compiled module is, read from its bytes
import blender_ext_tool  # scripts/blender_ext_tool.py: Blender's own extension build/validate tool
import verify_addon_install  # scripts/verify_addon_install.py: the --verify-install check

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCE = os.path.join(REPO, "python_addon", "gauss_stylization")
MANIFEST_TEMPLATE = os.path.join(REPO, "packaging", "blender_manifest.toml.in")
PACKAGE = "gauss_stylization"
ZIP_DATE = (1980, 1, 1, 0, 0, 0)
# CPython extension suffix, e.g. gauss_core.cpython-311-x86_64-linux-gnu.so
SO_PATTERN = re.compile(r"^gauss_core\.cpython-(?P<major>\d)(?P<minor>\d+)-(?P<platform>[^.]+)\.so$")

# Which Blender runs which Python (the module only loads in the Python it was built for): official
# blender.org releases, first and last inclusive (None: every later release so far; the next Python
# change will end it), with the numpy they bundle; a Linux distribution's blender package runs the
# system Python instead ("also"). The one place these facts are written.
BLENDER_FOR_PYTHON = {
    "3.10": {"official": ((3, 1), (4, 0)), "numpy": "1.x", "also": ()},
    "3.11": {"official": ((4, 1), (5, 0)), "numpy": "1.x", "also": ("Debian 12's blender package (3.4.1)",)},
    "3.13": {"official": ((5, 1), None), "numpy": "2.x", "also": ()},
}
EXTENSIONS_SINCE = (4, 2)  # the first Blender that installs extensions (blender_manifest.toml)
# Blender's extension platforms this project builds wheels for (release.yml), and the name each has in
# a classic zip's file name (Python's platform tags, which Blenders older than extensions know).
PLATFORMS = {"linux-x64": "linux_x86_64", "windows-x64": "win_amd64",
             "macos-arm64": "macosx_arm64", "macos-x64": "macosx_x86_64"}
# gauss_core-0.1.0-cp311-cp311-manylinux_2_28_x86_64.whl (no build tag)
WHEEL_PATTERN = re.compile(r"^gauss_core-(?P<version>[^-]+)-cp(?P<major>\d)(?P<minor>\d+)-cp\d+-(?P<platform>[^-]+)\.whl$")
# The module's file inside a wheel: .so (Linux, macOS) or .pyd (Windows).
MODULE_IN_WHEEL = re.compile(r"^gauss_core\.[^/]+\.(so|pyd)$")
# What the module in a wheel for each platform must be (scripts/binary_facts.py's format and arch), and
# the Python and platform its file name must carry (CPython's extension suffix: cpython-311-x86_64-linux-gnu,
# cp311-win_amd64, cpython-311-darwin).
BINARY_FOR_PLATFORM = {"linux-x64": ("ELF64", "x86_64"), "windows-x64": ("PE32+", "x86_64"),
                       "macos-arm64": ("Mach-O", "arm64"), "macos-x64": ("Mach-O", "x86_64")}
SUFFIX_FOR_PLATFORM = {"linux-x64": r"cpython-{XY}-x86_64-linux-gnu\.so", "windows-x64": r"cp{XY}-win_amd64\.pyd",
                       "macos-arm64": r"cpython-{XY}-darwin\.so", "macos-x64": r"cpython-{XY}-darwin\.so"}


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
    """"4.2 to 5.0", "5.1", or "5.1 and later" (last None)."""
    if last is None:
        return "%s and later" % release(first)
    return release(first) if first == last else "%s to %s" % (release(first), release(last))


def blender_ranges(python, addon_min):
    """Official Blender releases that load a module built for `python`, as (first, last) pairs of
    (major, minor), last None for "and later": for the classic zip, and for the extension zip (None: no
    extension Blender)."""
    row = BLENDER_FOR_PYTHON.get(python)
    if row is None:
        fail("the module was built for Python %s, which no Blender release runs (Blender runs %s): build "
             "it against Blender's Python (README, \"Which Blender can load this build\")"
             % (python, ", ".join(BLENDER_FOR_PYTHON)))
    first, last = row["official"]
    classic = (max(first, addon_min), last)
    extension = (max(first, EXTENSIONS_SINCE), last) if last is None or last >= EXTENSIONS_SINCE else None
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
        fail("built for %s; only Linux x86-64 build trees are packaged (other platforms: --wheels)"
             % match["platform"])
    return found[0], python, "cp%s%s-linux_x86_64" % (match["major"], match["minor"])


def facts_file(build_dir):
    facts = os.path.join(build_dir, "addon", PACKAGE, "core_facts.json")
    if not os.path.isfile(facts):
        fail("no core_facts.json in %s: build first (bash scripts/build.sh %s)"
             % (os.path.dirname(facts), build_dir))
    return facts


def python_files():
    """(path on disk, name inside the package) of the add-on's Python sources, its sub-packages'
    included ("run/session.py"), sorted."""
    files = []
    for folder, subfolders, names in os.walk(SOURCE):
        subfolders[:] = [name for name in subfolders if name != "__pycache__"]
        for name in names:
            if name.endswith(".py"):
                path = os.path.join(folder, name)
                files.append((path, os.path.relpath(path, SOURCE).replace(os.sep, "/")))
    files.sort(key=lambda entry: entry[1])
    if not any(name == "__init__.py" for _, name in files):
        fail("no __init__.py in %s" % SOURCE)
    return files


def write_zip(path, entries, stored=()):
    """entries: (name in zip, bytes, unix mode); names in `stored` are not compressed. Deterministic
    output: sorted entries, fixed timestamps and modes."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as archive:
        for name, data, mode in sorted(entries):
            info = zipfile.ZipInfo(name, date_time=ZIP_DATE)
            info.compress_type = zipfile.ZIP_STORED if name in stored else zipfile.ZIP_DEFLATED
            info.external_attr = (0o100000 | mode) << 16
            archive.writestr(info, data)


def make_reproducible(path):
    """Rewrites a zip of Blender's extension build with write_zip's order, timestamps and modes (Blender's
    tool stamps each entry with the file's or the current time, in directory order); the entries' bytes,
    the wheels' included, are unchanged."""
    with zipfile.ZipFile(path) as archive:
        entries = [(info.filename, archive.read(info), mode_of(info.filename)) for info in archive.infolist()]
        stored = {info.filename for info in archive.infolist() if info.compress_type == zipfile.ZIP_STORED}
    write_zip(path, entries, stored)


def read(path):
    with open(path, "rb") as handle:
        return handle.read()


def mode_of(name):
    return 0o755 if name.endswith((".so", ".pyd")) else 0o644


def toml_list(values):
    return "[%s]" % ", ".join('"%s"' % value for value in values)


def manifest_text(version, python, extension_range, platforms, wheel_paths):
    """blender_manifest.toml for the wheels of one Python (paths relative to the extension's root)."""
    with open(MANIFEST_TEMPLATE, encoding="utf-8") as handle:
        text = handle.read()
    first, last = extension_range
    # blender_version_max is the first release the extension does NOT support; none when no later
    # Blender is known to run another Python.
    maximum = ('blender_version_max = "%d.%d.0"' % (last[0], last[1] + 1) if last is not None else
               "# No blender_version_max: every Blender since %s runs Python %s so far." % (release(first), python))
    for placeholder, value in (("@VERSION@", version), ("@PYTHON@", python),
                               ("@BLENDER_MIN@", "%d.%d.0" % first), ("@BLENDER_MAX_LINE@", maximum),
                               ("@PLATFORMS@", toml_list(platforms)), ("@WHEELS@", toml_list(wheel_paths))):
        text = text.replace(placeholder, value)
    if re.search(r"@[A-Z_]+@", text):
        fail("unfilled placeholder in %s" % MANIFEST_TEMPLATE)
    manifest = tomllib.loads(text)  # must parse; Blender's validator checks the rest
    if manifest["id"] != PACKAGE:
        fail("manifest id must be %r" % PACKAGE)
    return text


def readme_text(kind, version, module_line, python, blender, addon_min):
    """README.txt of a zip: which Blender loads it, what it needs, which zip the other Blenders need."""
    row = BLENDER_FOR_PYTHON[python]
    loads = ["official Blender %s (Python %s, numpy %s)" % (releases(*blender), python, row["numpy"])]
    if kind == "add-on":
        loads += list(row["also"])
    others = ["  official Blender %s%s (Python %s): the zip whose name has -cp%s-"
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
        module_line,
        "",
        "Loads in: " + "; ".join(loads) + ".",
        "Other Blenders run another Python and cannot load this module; they need:",
        *others,
        "or a module built for their Python (source README, \"Which Blender can load this build\").",
        "",
        "Install: " + install,
        "",
    ])


def wheel_facts(wheel_path, blender_ext):
    """(python "3.11", Blender platform "linux-x64", classic tag "cp311-linux_x86_64", version) of a
    gauss_core wheel, the platform read with Blender's own rule (blender_ext.py)."""
    match = WHEEL_PATTERN.match(os.path.basename(wheel_path))
    if match is None:
        fail("%s is not a gauss_core wheel (gauss_core-VERSION-cpXY-cpXY-PLATFORM.whl)" % wheel_path)
    platforms = blender_ext.blender_platforms_from_wheel_platform(match["platform"])
    if len(platforms) != 1 or platforms[0] not in PLATFORMS:
        fail("%s is for %s; the extension ships %s" % (wheel_path, ", ".join(platforms), ", ".join(PLATFORMS)))
    return ("%s.%s" % (match["major"], match["minor"]), platforms[0],
            "cp%s%s-%s" % (match["major"], match["minor"], PLATFORMS[platforms[0]]), match["version"])


def module_from_wheel(wheel_path):
    """(file name, bytes) of the gauss_core module inside a wheel."""
    with zipfile.ZipFile(wheel_path) as wheel:
        found = [name for name in wheel.namelist() if MODULE_IN_WHEEL.match(name)]
        if len(found) != 1:
            fail("%s must hold one top-level gauss_core module, holds %s" % (wheel_path, found))
        return found[0], wheel.read(found[0])


def check_wheel_module(wheel_path, python, platform):
    """Refuses a wheel whose module is not what its tag says: file format and architecture for the
    platform, the Python it was built for, and the extension suffix of its file name."""
    wheel = os.path.basename(wheel_path)
    name, data = module_from_wheel(wheel_path)
    tag = WHEEL_PATTERN.match(wheel)["platform"]
    try:
        found = binary_facts.facts(data)
    except binary_facts.NotABinary as exc:
        fail("refusing %s: its module %s is no compiled module (%s)" % (wheel, name, exc))
    wanted = BINARY_FOR_PLATFORM[platform]
    problems = []
    if (found["format"], found["arch"]) != wanted:
        problems.append("it is %s, the tag %s needs %s %s" % (binary_facts.describe(found), tag, *wanted))
    if found["python"] != python:
        problems.append("it was built for Python %s, the tag cp%s needs %s"
                        % (found["python"] or "(unknown: no BUILT_FOR text, an old build)", python.replace(".", ""), python))
    suffix = SUFFIX_FOR_PLATFORM[platform].replace("{XY}", python.replace(".", ""))
    if not re.fullmatch(r"gauss_core\." + suffix, name):
        problems.append("its file name says another Python or system than the tag (expected gauss_core.%s)"
                        % suffix.replace("\\", ""))
    if problems:
        fail("refusing %s: its module %s does not match the wheel's tag: %s" % (wheel, name, "; ".join(problems)))


def wheel_module_line(python, platforms, wheel_names):
    linux = [name for name in wheel_names if "manylinux_" in name]
    glibc = re.search(r"manylinux_(\d+)_(\d+)_", linux[0]) if linux else None
    return "\n".join(["Solver module: the gauss_core wheel%s %s, built for Python %s (%s)."
                      % ("s" if len(wheel_names) > 1 else "", ", ".join(wheel_names), python, ", ".join(platforms))]
                     + (["On Linux it needs glibc %s.%s or newer and no other system library." % glibc.groups()]
                        if glibc else []))


def build_extensions(python, wheels, version, addon_min, facts, out_dir, blender_ext):
    """The extension zips of one Python's wheels, one per platform, by Blender's own tool; returns them."""
    _, extension_range = blender_ranges(python, addon_min)
    if extension_range is None:
        print("no extension zip for Python %s: Blender %s and later run another Python"
              % (python, release(EXTENSIONS_SINCE)))
        return []
    platforms = sorted({platform for _, platform in wheels}, key=list(PLATFORMS).index)
    names = sorted(os.path.basename(path) for path, _ in wheels)
    tag = "cp" + python.replace(".", "")
    with tempfile.TemporaryDirectory(prefix="gauss_extension_") as stage:
        for path, name in python_files() + [(facts, "core_facts.json")]:
            os.makedirs(os.path.dirname(os.path.join(stage, name)), exist_ok=True)
            shutil.copyfile(path, os.path.join(stage, name))
        os.makedirs(os.path.join(stage, "wheels"))
        for path, _ in wheels:
            shutil.copyfile(path, os.path.join(stage, "wheels", os.path.basename(path)))
        with open(os.path.join(stage, "README.txt"), "w", encoding="utf-8") as handle:
            handle.write(readme_text("extension", version, wheel_module_line(python, platforms, names), python,
                                     extension_range, addon_min))
        with open(os.path.join(stage, "blender_manifest.toml"), "w", encoding="utf-8") as handle:
            handle.write(manifest_text(version, python, extension_range, platforms,
                                       ["./wheels/" + name for name in names]))
        target = os.path.join(out_dir, "%s-%s-extension-%s.zip" % (PACKAGE, version, tag))
        made = [target.replace(".zip", "-%s.zip" % platform.replace("-", "_")) for platform in platforms]
        for path in made:
            if os.path.exists(path):
                os.remove(path)
        code, output = blender_ext_tool.run("build", "--source-dir", stage, "--output-filepath", target,
                                            "--split-platforms")
        missing = [path for path in made if not os.path.isfile(path)]
        if code != 0 or missing:
            fail("Blender's extension build failed (exit code %d, missing %s):\n%s" % (code, missing, output))
    for path in made:
        make_reproducible(path)
        code, output = blender_ext_tool.run("validate", path)
        if code != 0:
            fail("Blender's validator rejects %s:\n%s" % (path, output))
        print("extension zip (Blender %s, %s, validated): %s"
              % (releases(*extension_range), path.rsplit("-", 1)[1][:-4], path))
    return made


def build_classic_from_wheel(wheel_path, python, tag, version, addon_min, facts, out_dir):
    classic_range, _ = blender_ranges(python, addon_min)
    module_name, module_bytes = module_from_wheel(wheel_path)
    glibc = re.search(r"manylinux_(\d+)_(\d+)_", os.path.basename(wheel_path))
    line = "Solver module: %s (from %s), built for Python %s, %s.%s" % (
        module_name, os.path.basename(wheel_path), python, tag.split("-", 1)[1],
        "\nIt needs glibc %s.%s or newer and no other system library." % glibc.groups() if glibc else "")
    return write_classic(out_dir, version, tag, python, classic_range, addon_min,
                         [(module_name, module_bytes), ("core_facts.json", read(facts))], line)


def write_classic(out_dir, version, tag, python, classic_range, addon_min, extra_files, module_line):
    """The classic add-on zip: one folder gauss_stylization/ with the sources, the module and facts."""
    readme = readme_text("add-on", version, module_line, python, classic_range, addon_min)
    files = [(name, read(path)) for path, name in python_files()] + extra_files + [("README.txt", readme.encode())]
    path = os.path.join(out_dir, "%s-%s-addon-%s.zip" % (PACKAGE, version, tag))
    write_zip(path, [("%s/%s" % (PACKAGE, name), data, mode_of(name)) for name, data in files])
    print("classic add-on zip (official Blender %s%s): %s"
          % (releases(*classic_range), "".join(", " + a for a in BLENDER_FOR_PYTHON[python]["also"]), path))
    return path


def release_table(version, addon_min):
    """Markdown rows: which Blender gets which zip, derived from BLENDER_FOR_PYTHON and PLATFORMS (for the
    README; `package_addon.py --table` prints them)."""
    rows = ["| Blender | Python | numpy | zip (PLATFORM: %s) |" % ", ".join(p.replace("-", "_") for p in PLATFORMS),
            "| --- | --- | --- | --- |"]
    for python, row in sorted(BLENDER_FOR_PYTHON.items(), key=lambda item: item[1]["official"], reverse=True):
        tag = "cp" + python.replace(".", "")
        classic, extension = blender_ranges(python, addon_min)
        if extension is not None:
            rows.append("| %s | %s | %s | `%s-%s-extension-%s-PLATFORM.zip` (extension) |"
                        % (releases(*extension), python, row["numpy"], PACKAGE, version, tag))
        last_classic = classic[1] if extension is None else (EXTENSIONS_SINCE[0], EXTENSIONS_SINCE[1] - 1)
        if last_classic is None or last_classic >= classic[0]:
            rows.append("| %s | %s | %s | `%s-%s-addon-%s-TAG.zip` (classic add-on; TAG: %s) |"
                        % (releases(classic[0], last_classic), python, row["numpy"], PACKAGE, version, tag,
                           ", ".join(PLATFORMS.values())))
        for also in row["also"]:
            rows.append("| %s | %s | the system's | `%s-%s-addon-%s-linux_x86_64.zip` (classic add-on) |"
                        % (also, python, PACKAGE, version, tag))
    return rows


def main():
    if sys.argv[1:] == ["--table"]:
        info = addon_info()
        print("\n".join(release_table(".".join(map(str, info["version"])), tuple(info["blender"][:2]))))
        return
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("out_dir")
    parser.add_argument("--wheels", nargs="+", metavar="WHEEL",
                        help="gauss_core wheels: make the extension zips (one per platform) and a classic zip "
                             "per wheel from them instead of the classic zip of BUILD_DIR's module")
    parser.add_argument("--verify-install", action="store_true",
                        help="install the classic zip into a temporary Blender user config and use it")
    args = parser.parse_args()
    build_dir, out_dir = os.path.abspath(args.build_dir), os.path.abspath(args.out_dir)
    info = addon_info()
    version = ".".join(str(part) for part in info["version"])
    addon_min = tuple(info["blender"][:2])
    facts = facts_file(build_dir)
    os.makedirs(out_dir, exist_ok=True)
    this_python = "%d.%d" % sys.version_info[:2]
    to_verify = None

    if args.wheels:
        try:
            blender_ext = blender_ext_tool.module()
        except RuntimeError as exc:
            fail(str(exc))
        by_python = {}
        for path in args.wheels:
            python, platform, tag, wheel_version = wheel_facts(os.path.abspath(path), blender_ext)
            check_wheel_module(os.path.abspath(path), python, platform)
            if wheel_version != version:
                fail("%s is version %s, the add-on %s: rebuild it (bash scripts/build_wheel.sh)"
                     % (path, wheel_version, version))
            if any(platform == other for _, other in by_python.get(python, [])):
                fail("two wheels for Python %s on %s" % (python, platform))
            by_python.setdefault(python, []).append((os.path.abspath(path), platform))
            classic = build_classic_from_wheel(path, python, tag, version, addon_min, facts, out_dir)
            if python == this_python and platform == "linux-x64":
                to_verify = classic
        for python, wheels in sorted(by_python.items()):
            build_extensions(python, wheels, version, addon_min, facts, out_dir, blender_ext)
    else:
        so_path, python, tag = native_module(build_dir)
        classic_range, _ = blender_ranges(python, addon_min)
        so_name = os.path.basename(so_path)
        module_line = ("Solver module: %s, built for Python %s, Linux x86-64, on the machine that made "
                       "this zip (a local build: the zips made from wheels, whose glibc auditwheel checks, "
                       "name the glibc they need)." % (so_name, python))
        to_verify = write_classic(out_dir, version, tag, python, classic_range, addon_min,
                                  [(so_name, read(so_path)), ("core_facts.json", read(facts))], module_line)
        this_python = python
    if args.verify_install:
        if to_verify is None:
            fail("--verify-install needs a linux-x64 wheel for Python %s" % this_python)
        try:
            verify_addon_install.verify_install(to_verify, this_python, PACKAGE)
        except verify_addon_install.InstallCheckFailed as exc:
            fail(str(exc))


if __name__ == "__main__":
    main()
