"""The C++ tree's folder order (docs/architecture.md, "The C++ tree, by job"): includes go one way.

A file in cpp/src/F/ or cpp/include/gauss/F/ may include gauss headers of its own folder and of the
folders before it in FOLDERS, and gauss/settings.h; never of a later folder. Every source has its
header's folder, and every folder is listed, so a new folder has to take its place in the order.
"""
import re

from conftest import REPO

FOLDERS = ("util", "mesh", "collision", "sparse", "style", "solver", "proxy")  # bottom first
INCLUDE = re.compile(r'^\s*#\s*include\s+"gauss/(?:(\w+)/)?(\w+)\.h"', re.M)


def _files():
    for root in (REPO / "cpp" / "src", REPO / "cpp" / "include" / "gauss"):
        for path in sorted(root.rglob("*")):
            if path.suffix in (".h", ".cpp"):
                yield root, path


def test_every_file_is_in_a_listed_folder():
    loose = [str(path.relative_to(REPO)) for root, path in _files()
             if path.relative_to(root).parts[0] not in FOLDERS and path.name != "settings.h"]
    assert not loose, "files outside the folders by job: %s" % loose


def test_includes_go_one_way():
    upward = []
    for root, path in _files():
        if path.name == "settings.h":
            continue
        own = FOLDERS.index(path.relative_to(root).parts[0])
        for folder, name in INCLUDE.findall(path.read_text(encoding="utf-8")):
            if not folder:
                assert name == "settings", "%s includes gauss/%s.h outside any folder" % (path, name)
            elif FOLDERS.index(folder) > own:
                upward.append("%s -> gauss/%s/%s.h" % (path.relative_to(REPO), folder, name))
    assert not upward, "includes from a later folder: %s" % upward


def test_the_pattern_reads_the_include_form():
    # The pattern must read the include form the sources use, or the test above passes vacuously.
    assert INCLUDE.findall('#include "gauss/solver/gauss_solver.h"\n#include "gauss/settings.h"') == [
        ("solver", "gauss_solver"), ("", "settings")]
