#!/usr/bin/env python3
"""Checks a cross-built gauss_core module (scripts/cross_check.sh) against what its platform needs.

    python3 scripts/check_cross_module.py PLATFORM PYTHON MINOS FILE
        PLATFORM  windows-x64, macos-arm64 or macos-x64;  PYTHON  e.g. 3.13;  MINOS  e.g. 11.0 (macOS)

Prints the end of cross_check's line for it ("built, imports python313.dll KERNEL32.dll msvcrt.dll" or
"built, minos 11.0, ad-hoc signed") and exits 0, or exits 1 with what is wrong:
  - Windows: a PE32+ x86-64 DLL that exports PyInit_gauss_core alone and imports pythonXY.dll of its
    Python and otherwise only DLLs every Windows has (no MinGW runtime: libstdc++, libgcc, winpthread);
  - macOS: a Mach-O file of the platform's architecture, for MINOS (LC_BUILD_VERSION), importing only
    the system's libSystem and libc++, and on arm64 an ad-hoc code signature whose page hashes match
    (Apple Silicon refuses to load unsigned code);
  - both: the Python it says it was built for (binary_facts.py) is PYTHON.
"""

import fnmatch
import os
import sys

import binary_facts

# DLLs of every Windows (10 and later): the kernel, the old C runtime MinGW links against, and the
# Universal CRT's API sets (what MSVC-built modules import).
WINDOWS_SYSTEM_DLLS = ("kernel32.dll", "msvcrt.dll", "api-ms-win-crt-*.dll")
MACOS_SYSTEM_LIBRARIES = ("/usr/lib/libSystem.B.dylib", "/usr/lib/libc++.1.dylib")
ARCH = {"windows-x64": ("PE32+", "x86_64"), "macos-arm64": ("Mach-O", "arm64"), "macos-x64": ("Mach-O", "x86_64")}


def check(platform, python, minos, data):
    """(True, line end) or (False, problems)."""
    facts = binary_facts.facts(data)
    problems = []
    if (facts["format"], facts["arch"]) != ARCH[platform]:
        problems.append("a %s file, not %s %s" % (binary_facts.describe(facts), *ARCH[platform]))
    if facts["python"] != python:
        problems.append("built for Python %s, not %s" % (facts["python"], python))
    if platform == "windows-x64":
        dll = "python%s.dll" % python.replace(".", "")
        pythons = [name for name in facts["imports"] if name.lower().startswith("python")]
        others = [name for name in facts["imports"] if name not in pythons]
        if [name.lower() for name in pythons] != [dll]:
            problems.append("imports %s, not %s alone of Python's DLLs" % (pythons, dll))
        foreign = [name for name in others
                   if not any(fnmatch.fnmatch(name.lower(), pattern) for pattern in WINDOWS_SYSTEM_DLLS)]
        if foreign:
            problems.append("imports DLLs that not every Windows has: %s" % ", ".join(foreign))
        if facts.get("exports") != ["PyInit_gauss_core"]:
            problems.append("exports %s, not PyInit_gauss_core alone" % (facts.get("exports") or "nothing"))
        line = "built, imports " + " ".join(pythons + others)
    else:
        if facts.get("minos") != minos:
            problems.append("minimum macOS %s, not %s" % (facts.get("minos"), minos))
        foreign = [name for name in facts["imports"] if name not in MACOS_SYSTEM_LIBRARIES]
        if foreign:
            problems.append("links libraries beyond the system's libSystem and libc++: %s" % ", ".join(foreign))
        line = "built, minos %s" % facts.get("minos")
        if platform == "macos-arm64":
            if facts.get("signature") != "ad-hoc":
                problems.append("code signature: %s (arm64 needs an ad-hoc one at least)" % facts.get("signature"))
            line += ", ad-hoc signed"
        elif facts.get("signature") == "ad-hoc":
            line += ", ad-hoc signed"
    return (not problems), (line if not problems else "; ".join(problems))


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ARCH:
        sys.exit(__doc__)
    platform, python, minos, path = sys.argv[1:]
    with open(path, "rb") as handle:
        data = handle.read()
    try:
        good, text = check(platform, python, minos, data)
    except binary_facts.NotABinary as exc:
        good, text = False, str(exc)
    if not good:
        sys.exit("%s: %s" % (os.path.basename(path), text))
    print(text)


if __name__ == "__main__":
    main()
