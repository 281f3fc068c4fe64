"""README.md's "Which zip for which Blender" table says what the scripts say.

Its Blender ranges, Pythons and zip kinds are those package_addon.py derives from BLENDER_FOR_PYTHON
(`package_addon.py --table`), and every Blender release scripts/test_blender_versions.sh runs the suite
in (scripts/blender_versions.txt) is named, with its numpy, in the row of the range that holds it.
"""
import re
import sys

from conftest import REPO

sys.path.insert(0, str(REPO / "scripts"))
import package_addon  # noqa: E402

SECTION = "## Which zip for which Blender"


def readme_rows():
    """The README table's rows as lists of cells (header and separator left out)."""
    text = (REPO / "README.md").read_text(encoding="utf-8")
    section = text[text.index(SECTION):]
    section = section[:section.index("\n## ", len(SECTION))]
    rows = [[cell.strip() for cell in line.strip().strip("|").split("|")]
            for line in section.splitlines() if line.startswith("|")]
    return rows[2:]


def script_rows():
    info = package_addon.addon_info()
    table = package_addon.release_table(".".join(map(str, info["version"])), tuple(info["blender"][:2]))
    return [[cell.strip() for cell in line.strip().strip("|").split("|")] for line in table[2:]]


def releases_run():
    """(bpy version, numpy version) of every release line of scripts/blender_versions.txt."""
    lines = (REPO / "scripts" / "blender_versions.txt").read_text(encoding="utf-8").splitlines()
    return [(fields[1], fields[3]) for fields in (line.split() for line in lines)
            if fields and fields[0] == "release"]


def blender_cell(cell):
    """'Debian 12's `blender` (3.4.1)' and "Debian 12's blender package (3.4.1)" name the same Blender."""
    return re.sub(r"[`]|package ", "", cell)


def test_the_rows_are_the_scripts_rows_in_order():
    readme, scripts = readme_rows(), script_rows()
    assert [blender_cell(row[0]) for row in readme] == [blender_cell(row[0]) for row in scripts]
    for ours, theirs in zip(readme, scripts):
        assert ours[1].startswith(theirs[1] + ","), (ours, theirs)  # the Python
        kind = "extension" if "(extension)" in theirs[3] else "addon"
        tag = re.search(r"-(cp\d+)-", theirs[3]).group(1)
        assert "-%s-%s-" % (kind, tag) in ours[2], (ours, theirs)


def in_range(version, blender):
    """Whether bpy `version` ("4.5.15") is in a README range ("4.2 to 5.0", "5.1 and later", "4.1")."""
    numbers = [tuple(map(int, found.split("."))) for found in re.findall(r"\d+\.\d+", blender)]
    release = tuple(map(int, version.split(".")[:2]))
    if "and later" in blender:
        return release >= numbers[0]
    return numbers[0] <= release <= numbers[-1]


def test_every_tested_release_is_named_with_its_numpy_in_its_row():
    rows = [row for row in readme_rows() if not row[0].startswith("Debian")]
    for version, numpy in releases_run():
        row = next(row for row in rows if in_range(version, row[0]))
        linux = row[3]
        assert "bpy" in linux and version in linux, (version, row)
        named = linux[linux.index(version):]
        assert re.match(r"[\d.]+(, [\d.]+)* \(numpy %s\)" % re.escape(numpy), named) or \
            ("numpy %s" % numpy) in named.split(")")[0], (version, numpy, linux)


def test_no_row_claims_a_bpy_run_that_the_script_does_not_make():
    tested = {version for version, _ in releases_run()}
    for row in readme_rows():
        claims = re.sub(r"\(numpy [^)]*\)", "", row[3]) if row[3].startswith("suite run in bpy") else ""
        for claimed in re.findall(r"\b\d+\.\d+\.\d+\b", claims):
            assert claimed in tested, (claimed, row)


def test_cross_built_claims_are_the_pythons_cross_check_builds():
    # scripts/cross_check.sh builds the module for every Python an extension zip is made for; a row may
    # claim "module cross-built and inspected (cpXY)" for those only, and each such row must claim it.
    built = {"cp" + python.replace(".", "") for python in package_addon.BLENDER_FOR_PYTHON
             if package_addon.blender_ranges(python, (0, 0))[1]}
    script = (REPO / "scripts" / "cross_check.sh").read_text(encoding="utf-8")
    assert "blender_ranges(v, (0, 0))[1]" in script  # the same rule picks the Pythons there
    for row in readme_rows():
        tag = re.search(r"-(cp\d+)-", row[2]).group(1)
        for cell in row[4:6]:
            claims = re.findall(r"module cross-built and inspected \((cp\d+)\)", cell)
            assert all(claim == tag for claim in claims), (row, claims)
            assert bool(claims) == (tag in built) or cell == "n/a", (row, built)
