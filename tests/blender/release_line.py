"""One release's result line of scripts/test_blender_versions.sh, from the suite's JUnit report.

    python release_line.py REPORT_XML PYTEST_STATUS    (run by the Python that ran the suite, with `bpy`)

Prints "blender 4.5.15 (Python 3.11.7, numpy 1.26.4): N passed, M failed, K skipped": the Blender
version as bpy reports it, the Python and numpy this interpreter runs, and the counts (errors count as
failed). A missing or unreadable report (the suite crashed) and a non-zero status with no failure
counted (pytest itself failed, e.g. no tests collected) count as one failure.
"""

import platform
import sys
import xml.etree.ElementTree as ElementTree

import bpy
import numpy


def counts(report):
    """(passed, failed, skipped) over every <testsuite> of the report."""
    root = ElementTree.parse(report).getroot()
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    total = failed = skipped = 0
    for suite in suites:
        total += int(suite.get("tests", 0))
        failed += int(suite.get("failures", 0)) + int(suite.get("errors", 0))
        skipped += int(suite.get("skipped", 0))
    return total - failed - skipped, failed, skipped


def main():
    report, status = sys.argv[1], int(sys.argv[2])
    try:
        passed, failed, skipped = counts(report)
    except (OSError, ElementTree.ParseError, ValueError):
        passed, failed, skipped = 0, 1, 0
    if status != 0 and failed == 0:
        failed = 1
    version = bpy.app.version_string.split()[0]  # without an " LTS"/" Alpha" suffix
    print("blender %s (Python %s, numpy %s): %d passed, %d failed, %d skipped"
          % (version, platform.python_version(), numpy.__version__, passed, failed, skipped))


main()
