#!/usr/bin/env python3
"""What a built gauss_core module needs from the Linux system it loads on, read with readelf.

    python3 scripts/module_reach.py MODULE.so

prints the shared libraries the module needs, the newest glibc symbol version it references (with the
symbols that need it) and what it exports, and exits 1 if any of it is beyond the allowance below.
tests/python/test_module_reach.py runs the same check on every build; scripts/package_addon.py writes
the glibc the module needs into each zip's README.

The allowance, which README.md ("Which Blender can load this build") explains:
  - NEEDED libraries: glibc's own only. ld-linux-x86-64.so.2, glibc's dynamic loader, is listed because
    it provides __tls_get_addr, with which a dlopen()ed module reaches its thread_local variables (the
    thread pool's and the C++ runtime's); it is part of every glibc.
  - glibc symbol versions up to GLIBC_2.28, what official Blender builds target; no version of any
    other library (GLIBCXX_, CXXABI_, GCC_: the C++ runtime and libgcc are linked in statically).
  - exported: PyInit_gauss_core, Python's entry point, and nothing else.
"""

import re
import subprocess
import sys

ALLOWED_NEEDED = ("libc.so.6", "libm.so.6", "libpthread.so.0", "libdl.so.2", "ld-linux-x86-64.so.2")
GLIBC_ALLOWANCE = (2, 28)
EXPORTS = ("PyInit_gauss_core",)

_GLIBC = re.compile(r"^GLIBC_(\d+(?:\.\d+)*)$")


def _readelf(*args):
    try:
        return subprocess.run(["readelf", "-W", *args], check=True, capture_output=True, text=True).stdout
    except FileNotFoundError:
        raise RuntimeError("readelf not found: install binutils") from None
    except subprocess.CalledProcessError as exc:
        raise RuntimeError("readelf %s failed: %s" % (" ".join(args), exc.stderr.strip())) from None


def needed_libraries(path):
    """The module's NEEDED entries, in order."""
    return re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", _readelf("-d", path))


def dynamic_symbols(path):
    """(name, version or None, defined) of every dynamic symbol."""
    symbols = []
    for line in _readelf("--dyn-syms", path).splitlines():
        fields = line.split()
        if len(fields) < 8 or not fields[0].rstrip(":").isdigit():
            continue
        name, version = fields[7], None
        if "@" in name:
            name, _, version = name.partition("@")
            version = version.lstrip("@")
        symbols.append((name, version, fields[6] != "UND"))
    return symbols


def required_versions(path):
    """{version name: sorted symbol names} of the versions the module needs from other libraries.

    Read from the version-needs section, so a version without any symbol counts as well."""
    _, _, needs_section = _readelf("-V", path).partition("Version needs section")
    needs = {name: [] for name in re.findall(r"Name: (\S+)\s+Flags:", needs_section)}
    for name, version, defined in dynamic_symbols(path):
        if version is not None and not defined:
            needs.setdefault(version, []).append(name)
    return {version: sorted(names) for version, names in needs.items()}


def glibc_version(version_name):
    """(2, 28) for "GLIBC_2.28"; None for a version of another library."""
    match = _GLIBC.match(version_name)
    return tuple(int(part) for part in match.group(1).split(".")) if match else None


def newest_glibc(path):
    """The newest glibc version the module references, e.g. (2, 17); None if it needs no glibc."""
    versions = [glibc_version(v) for v in required_versions(path)]
    return max((v for v in versions if v is not None), default=None)


def problems(path):
    """Everything about the module that is beyond the allowance, as readable lines (empty if none)."""
    found = []
    for library in needed_libraries(path):
        if library not in ALLOWED_NEEDED:
            found.append("needs %s, which is not part of glibc (allowed: %s)"
                         % (library, ", ".join(ALLOWED_NEEDED)))
    for version, symbols in sorted(required_versions(path).items()):
        numbers = glibc_version(version)
        if numbers is None:
            found.append("needs symbol version %s (%s): not glibc's" % (version, ", ".join(symbols[:5])))
        elif numbers > GLIBC_ALLOWANCE:
            found.append("needs %s (%s), newer than GLIBC_%s" % (
                version, ", ".join(symbols) or "no symbol named", ".".join(map(str, GLIBC_ALLOWANCE))))
    exported = sorted(name for name, _, defined in dynamic_symbols(path) if defined)
    extra = [name for name in exported if name not in EXPORTS]
    if extra:
        found.append("exports %d symbols besides %s, e.g. %s"
                     % (len(extra), ", ".join(EXPORTS), ", ".join(extra[:5])))
    return found


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    path = argv[1]
    newest = newest_glibc(path)
    print("NEEDED: %s" % ", ".join(needed_libraries(path)))
    print("newest glibc symbol version: %s" % ("GLIBC_" + ".".join(map(str, newest)) if newest else "none"))
    exported = sorted(name for name, _, defined in dynamic_symbols(path) if defined)
    print("exports %d symbols: %s%s" % (len(exported), ", ".join(exported[:5]), ", ..." * (len(exported) > 5)))
    found = problems(path)
    for line in found:
        print("BEYOND THE ALLOWANCE: " + line)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
