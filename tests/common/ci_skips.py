"""A pytest plugin for both suites (tests/python and, inside Blender, tests/blender): under CI (CI=true)
a skipped test is a failure unless its reason is on ALLOWED below, because on CI's machine every test
has what it needs, and a skip there hides a missing install step or a missing file (../shared/meshes).

The closing summary prints the skip count with the allow-list it was checked against, so a log says how
many tests did not run and why. Loaded by both conftest.py files (pytest_plugins).
"""
import os
import re

import pytest

# (why a skip is allowed, the pattern its reason must match). Nothing else may skip under CI.
ALLOWED = [
    ("the numpy 2 checks run in scripts/test_numpy2.sh's venvs, not under the system numpy 1",
     r"^needs numpy 2 \(scripts/test_numpy2\.sh"),
    ("what Blender 4.2 added (extensions, command line commands) runs in the bpy releases "
     "(scripts/test_blender_versions.sh), not in Debian's 3.4.1",
     r"^Blender 3\.\d+\.\d+ has no .* \(4\.2 and later\)$"),
    ("in the bpy releases the whole suite runs on the installed extension, which is what that test checks "
     "in Debian's Blender", r"^Blender as a module: the suite itself runs on the installed extension"),
]
# The release workflow tests its wheels on GitHub's machines, in a checkout without the steering repo's
# shared/ beside it and without Debian's packages, and says so (GAUSS_RELEASE_WHEEL_TESTS=1 in
# .github/workflows/release.yml); on the project's machines and CI these must be there.
if os.environ.get("GAUSS_RELEASE_WHEEL_TESTS") == "1":
    ALLOWED += [
        ("a release wheel's tests: no ../shared/meshes", r"^\.\./shared/meshes not present"),
        ("a release wheel's tests: no Debian pybind11-dev", r"^needs Debian's pybind11-dev"),
    ]

_skips = []  # (nodeid, reason, allowed) of every skip, whether CI turned it into a failure or not


def in_ci():
    return os.environ.get("CI", "").lower() == "true"


def allowed(reason):
    return any(re.search(pattern, reason) for _why, pattern in ALLOWED)


def _reason(report):
    longrepr = report.longrepr
    if isinstance(longrepr, tuple) and len(longrepr) == 3:  # (path, line, "Skipped: why")
        return re.sub(r"^Skipped: ", "", str(longrepr[2]))
    return str(longrepr)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if not report.skipped or hasattr(report, "wasxfail"):
        return
    reason = _reason(report)
    _skips.append((report.nodeid, reason, allowed(reason)))
    if in_ci() and not allowed(reason):
        report.outcome = "failed"
        report.longrepr = ("skipped under CI=true, and the reason is not on the allow-list of "
                           "tests/common/ci_skips.py: %s" % reason)


def pytest_terminal_summary(terminalreporter):
    write = terminalreporter.write_line
    on_list = sum(1 for _nodeid, _reason, ok in _skips if ok)
    write("skipped: %d, %d of them on the allow-list%s" % (
        len(_skips), on_list, " (CI=true: any other skip is a failure)" if in_ci() else ""))
    for why, pattern in ALLOWED:
        write("  allow-list: %s  [%s]" % (why, pattern))
    for nodeid, reason, ok in _skips:
        write("  %s %s: %s" % ("allowed" if ok else "NOT ALLOWED", nodeid, reason))
