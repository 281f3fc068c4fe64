#!/usr/bin/env python3
"""CPython's headers (and, for Windows, an import library) for building gauss_core for another system.

    python3 scripts/cross_cpython.py CACHE_DIR PYTHON TARGET     (PYTHON 3.11 or 3.13; TARGET windows or macos)

Prints one line, the folder to give CMake as Python_INCLUDE_DIR, then for windows a second line, the
import library of pythonXY.dll to give as Python_LIBRARY. Everything is made once under
CACHE_DIR/PYTHON/ and reused (scripts/cross_check.sh keeps CACHE_DIR outside the work tree).

Where it comes from (docs/building.md, "Cross-built modules"):
  - CPython's Include/ and, for Windows, PC/pyconfig.h (the hand-written configuration every Windows
    build of CPython uses): from Debian's source package of that Python (`apt-get source`), whose
    upstream tarball is pinned by SHA-256 in packaging/cpython-sources.txt;
  - macOS has no such static pyconfig.h (configure writes it, and it cannot run for macOS here): the one
    Debian's libpython3.X-dev ships (configure's answers on x86-64 Linux, same upstream version), with
    the three feature-test macros that configure leaves out on macOS removed;
  - pythonXY.dll's import library: a .def of every name CPython's headers declare exported
    (PyAPI_FUNC/PyAPI_DATA), turned into a MinGW import library by dlltool. A module that needs a name
    the DLL does not export fails to link.
apt-get runs with a private configuration and state under CACHE_DIR (Debian's archive, signed by the
keyring Debian installs), so the machine's own apt sources are not touched.
"""

import hashlib
import os
import re
import shutil
import subprocess
import sys
import tarfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PINS = os.path.join(REPO, "packaging", "cpython-sources.txt")
KEYRING = "/usr/share/keyrings/debian-archive-keyring.gpg"
ARCHIVE = "http://deb.debian.org/debian"
DLLTOOL = "x86_64-w64-mingw32-dlltool"
# Names CPython's headers declare exported from pythonXY.dll: PyAPI_FUNC(type) name( / PyAPI_DATA(type) name
EXPORT = re.compile(r"PyAPI_(FUNC|DATA)\(((?:[^()]|\([^()]*\))*)\)\s*\(?\s*([A-Za-z_]\w*)")
# Feature-test macros configure defines on Linux and leaves out on macOS (configure.ac: define_xopen_source=no
# for Darwin), which would hide BSD parts of macOS's own headers.
STAMP = " exports _?Py*"  # the rule that made the files: a change remakes them
NOT_ON_MACOS = ("_POSIX_C_SOURCE", "_XOPEN_SOURCE", "_XOPEN_SOURCE_EXTENDED")


def fail(message):
    sys.exit("cross_cpython.py: " + message)


def pins():
    table = {}
    with open(PINS, encoding="utf-8") as handle:
        for line in handle:
            if line.strip() and not line.startswith("#"):
                python, suite, package, tarball, sha = line.split()
                table[python] = dict(suite=suite, package=package, tarball=tarball, sha256=sha)
    return table


def sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def apt(cache):
    """apt-get/apt-cache with sources and state of their own under cache/apt."""
    state = os.path.join(cache, "apt")
    sources = os.path.join(state, "sources.list")
    if not os.path.isfile(sources):
        os.makedirs(os.path.join(state, "lists", "partial"), exist_ok=True)
        os.makedirs(os.path.join(state, "archives", "partial"), exist_ok=True)
        os.makedirs(os.path.join(state, "cache"), exist_ok=True)
        with open(sources, "w", encoding="utf-8") as handle:
            for suite in sorted({row["suite"] for row in pins().values()}):
                handle.write("deb-src [signed-by=%s] %s %s main\n" % (KEYRING, ARCHIVE, suite))
                handle.write("deb [arch=amd64 signed-by=%s] %s %s main\n" % (KEYRING, ARCHIVE, suite))
    options = ["-o", "Dir::Etc::SourceList=" + sources, "-o", "Dir::Etc::SourceParts=/dev/null",
               "-o", "Dir::State::Lists=" + os.path.join(state, "lists"),
               "-o", "Dir::Cache=" + os.path.join(state, "cache"),
               "-o", "Dir::Cache::Archives=" + os.path.join(state, "archives"),
               "-o", "Debug::NoLocking=1", "-o", "APT::Sandbox::User=root", "-q"]
    return options


def run(command, cwd=None):
    result = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        fail("%s failed:\n%s" % (" ".join(command), result.stdout[-3000:]))
    return result.stdout


def downloads(cache, python, pin):
    """The pinned source tarball and the libpython-dev package of that upstream version, fetched once."""
    folder = os.path.join(cache, python, "downloads")
    os.makedirs(folder, exist_ok=True)
    tarball = os.path.join(folder, pin["tarball"])
    upstream = re.search(r"_([\d.]+)\.orig", pin["tarball"]).group(1)
    debs = [name for name in os.listdir(folder) if name.startswith("libpython%s-dev_%s-" % (python, upstream))]
    if os.path.isfile(tarball) and sha256(tarball) == pin["sha256"] and debs:
        return tarball, os.path.join(folder, debs[0])
    options = apt(cache)
    print("cross_cpython: fetching Debian's %s sources (%s)" % (pin["package"], pin["suite"]), file=sys.stderr)
    if not any(name.endswith("Sources") for name in os.listdir(os.path.join(cache, "apt", "lists"))):
        run(["apt-get", *options, "update"])
    run(["apt-get", *options, "source", "--download-only", "--only-source", "%s/%s" % (pin["package"], pin["suite"])],
        cwd=folder)
    if not os.path.isfile(tarball):
        fail("Debian's %s/%s no longer has %s (it moved to another upstream version): update "
             "packaging/cpython-sources.txt" % (pin["package"], pin["suite"], pin["tarball"]))
    if sha256(tarball) != pin["sha256"]:
        fail("%s does not have the SHA-256 pinned in packaging/cpython-sources.txt" % tarball)
    run(["apt-get", *options, "download", "libpython%s-dev/%s" % (python, pin["suite"])], cwd=folder)
    debs = [name for name in os.listdir(folder) if name.startswith("libpython%s-dev_%s-" % (python, upstream))]
    if not debs:
        fail("Debian's libpython%s-dev in %s is not of upstream version %s" % (python, pin["suite"], upstream))
    return tarball, os.path.join(folder, debs[0])


def extract(tarball, prefix, destination):
    """The members of tarball under prefix (e.g. Python-3.11.2/Include/), into destination."""
    with tarfile.open(tarball) as archive:
        top = archive.next().name.split("/")[0]
        members = [m for m in archive.getmembers() if m.name.startswith("%s/%s" % (top, prefix)) and m.isfile()]
        for member in members:
            member.name = member.name[len(top) + 1 + len(prefix):].lstrip("/") or os.path.basename(member.name)
            archive.extract(member, destination, filter="data")
    return len(members)


def exports(include):
    """{name: "FUNC"|"DATA"} of everything the headers declare exported."""
    found = {}
    for folder, _, names in os.walk(include):
        for name in names:
            if name.endswith(".h"):
                with open(os.path.join(folder, name), encoding="utf-8", errors="replace") as handle:
                    text = re.sub(r"/\*.*?\*/", " ", handle.read(), flags=re.S)
                for kind, _, symbol in EXPORT.findall(text):
                    # Only CPython's own names: pthread_stubs.h declares pthread_* for WASI with PyAPI_FUNC,
                    # which are no exports of pythonXY.dll and would clash with winpthread's.
                    if re.match(r"_?Py", symbol):
                        found[symbol] = kind
    return found


def prepare(cache, python, target):
    pin = pins().get(python) or fail("no pin for Python %s in %s" % (python, PINS))
    base = os.path.join(cache, python)
    include = os.path.join(base, target + "-include")
    stamp = os.path.join(base, target + ".done")
    dll = "python%s" % python.replace(".", "")
    library = os.path.join(base, "lib%s.dll.a" % dll)
    if os.path.isfile(stamp) and open(stamp, encoding="utf-8").read() == pin["sha256"] + STAMP:
        return include, library
    tarball, deb = downloads(cache, python, pin)
    shutil.rmtree(include, ignore_errors=True)
    if extract(tarball, "Include/", include) < 100:
        fail("%s has no Include/ folder" % tarball)
    if target == "windows":
        pc = os.path.join(base, "pc")
        shutil.rmtree(pc, ignore_errors=True)
        extract(tarball, "PC/", pc)
        # 3.13 keeps it as pyconfig.h.in, which the Windows build copies unchanged unless it builds the
        # free-threaded variant (Py_GIL_DISABLED), which Blender does not run.
        source = next(os.path.join(pc, n) for n in ("pyconfig.h", "pyconfig.h.in") if os.path.isfile(os.path.join(pc, n)))
        shutil.copyfile(source, os.path.join(include, "pyconfig.h"))
        names = exports(include)
        definition = os.path.join(base, dll + ".def")
        with open(definition, "w", encoding="utf-8") as handle:
            handle.write("LIBRARY %s.dll\nEXPORTS\n" % dll)
            handle.writelines("  %s%s\n" % (name, " DATA" if kind == "DATA" else "") for name, kind in sorted(names.items()))
        run([DLLTOOL, "--input-def", definition, "--output-lib", library, "--dllname", dll + ".dll"])
    else:
        unpacked = os.path.join(base, "deb")
        shutil.rmtree(unpacked, ignore_errors=True)
        run(["dpkg-deb", "-x", deb, unpacked])
        linux = os.path.join(unpacked, "usr", "include", "x86_64-linux-gnu", "python" + python, "pyconfig.h")
        with open(linux, encoding="utf-8") as handle:
            text = handle.read()
        for macro in NOT_ON_MACOS:
            text, count = re.subn(r"(?m)^#define %s\b.*$" % macro, "/* %s: not defined on macOS */" % macro, text)
            if count != 1:
                fail("%s defines %s %d times, expected once" % (linux, macro, count))
        with open(os.path.join(include, "pyconfig.h"), "w", encoding="utf-8") as handle:
            handle.write("/* Made by scripts/cross_cpython.py from %s (Debian's x86-64 Linux configure of\n"
                         "   CPython %s), for compiling against on macOS. */\n" % (os.path.basename(deb), python))
            handle.write(text)
    with open(stamp, "w", encoding="utf-8") as handle:
        handle.write(pin["sha256"] + STAMP)
    return include, library


def main():
    if len(sys.argv) != 4 or sys.argv[3] not in ("windows", "macos"):
        sys.exit(__doc__)
    cache, python, target = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    include, library = prepare(cache, python, target)
    print(include)
    if target == "windows":
        print(library)


if __name__ == "__main__":
    main()
