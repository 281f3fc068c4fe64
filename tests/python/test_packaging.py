"""scripts/package_addon.py: what each zip holds and which Blender it claims, derived from BLENDER_FOR_PYTHON.

The extension zips are made from the real gauss_core wheel for this Python (scripts/build_wheel.sh) by
Blender's own tooling and must pass Blender's own validator (blender_ext.py, scripts/blender_ext_tool.py).
Only linux-x64 wheels can be built here; to check that --split-platforms gives each platform its own zip
with only its own wheel, a Windows wheel is made from the Linux one with its module replaced by a
minimal PE32+ DLL of the right Python (pe_module.py; test data only: that zip is never installed
anywhere). The packager refuses a wheel whose module is not what its tag says: a Linux wheel merely
renamed to a Windows or another Python's name.
"""
import shutil
import subprocess
import sys
import tomllib
import zipfile

import pytest

from conftest import BUILD, REPO
from pe_module import pe_module
from wheel_build import TAG, build_wheel

sys.path.insert(0, str(REPO / "scripts"))
import blender_ext_tool  # noqa: E402
import package_addon  # noqa: E402

ADDON_MIN = (3, 4)  # an add-on that needs Blender 3.4 or later
PYTHON = "%d.%d" % sys.version_info[:2]
VERSION = ".".join(str(part) for part in package_addon.addon_info()["version"])
SCRIPT = REPO / "scripts" / "package_addon.py"
# Every Python file of the add-on, its sub-packages' too ("run/session.py"): what each zip must hold.
ADDON_SOURCES = sorted(path.relative_to(REPO / "python_addon" / "gauss_stylization").as_posix()
                       for path in (REPO / "python_addon" / "gauss_stylization").rglob("*.py")
                       if "__pycache__" not in path.parts)


def test_blender_ranges_follow_the_python_version():
    assert package_addon.blender_ranges("3.10", ADDON_MIN) == (((3, 4), (4, 0)), None)  # no extension Blender
    assert package_addon.blender_ranges("3.11", ADDON_MIN) == (((4, 1), (5, 0)), ((4, 2), (5, 0)))
    # 3.13: Blender 5.1 and every later release so far (5.2 LTS included): no last release.
    assert package_addon.blender_ranges("3.13", ADDON_MIN) == (((5, 1), None), ((5, 1), None))
    with pytest.raises(SystemExit, match="no Blender release runs"):
        package_addon.blender_ranges("3.12", ADDON_MIN)


@pytest.mark.parametrize("python, first, first_unsupported",
                         [("3.11", "4.2.0", "5.1.0"), ("3.13", "5.1.0", None)])
def test_manifest_range(python, first, first_unsupported):
    extension_range = package_addon.blender_ranges(python, ADDON_MIN)[1]
    manifest = tomllib.loads(package_addon.manifest_text("1.2.3", python, extension_range, ["linux-x64"],
                                                         ["./wheels/w.whl"]))
    assert manifest["blender_version_min"] == first
    assert manifest.get("blender_version_max") == first_unsupported


@pytest.fixture(scope="module")
def input_wheels(tmp_path_factory):
    """This Python's wheel and a Windows-named copy of it: (Linux wheel, Windows wheel) paths."""
    wheel = build_wheel()
    wheels = tmp_path_factory.mktemp("wheels")
    linux = wheels / wheel.name
    shutil.copy(wheel, linux)
    windows = wheels / wheel.name.replace("manylinux_2_28_x86_64", "win_amd64")
    windows_wheel(wheel, windows)
    return linux, windows


@pytest.fixture(scope="module")
def packaged(tmp_path_factory, input_wheels):
    """package_addon.py --wheels with input_wheels: (out dir, stdout, {platform: wheel name})."""
    linux, windows = input_wheels
    out = tmp_path_factory.mktemp("zips")
    result = subprocess.run([sys.executable, str(SCRIPT), str(BUILD), str(out), "--wheels", str(linux), str(windows)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    return out, result.stdout, {"linux-x64": linux.name, "windows-x64": windows.name}


def windows_wheel(linux_wheel, path):
    """A copy of the Linux wheel for Windows: the module a PE32+ DLL for this Python, named as CPython
    names it there."""
    with zipfile.ZipFile(linux_wheel) as source, zipfile.ZipFile(path, "w") as target:
        for item in source.infolist():
            if item.filename.startswith("gauss_core.cpython-"):
                target.writestr(zipfile.ZipInfo("gauss_core.%s-win_amd64.pyd" % TAG, item.date_time), pe_module(PYTHON))
            else:
                target.writestr(item, source.read(item))


def package(out, *wheels):
    return subprocess.run([sys.executable, str(SCRIPT), str(BUILD), str(out), "--wheels", *map(str, wheels)],
                          capture_output=True, text=True)


def test_a_renamed_linux_wheel_is_refused(tmp_path):
    wheel = build_wheel()
    renamed = tmp_path / wheel.name.replace("manylinux_2_28_x86_64", "win_amd64")
    shutil.copy(wheel, renamed)
    result = package(tmp_path / "zips", renamed)
    assert result.returncode != 0
    message = result.stderr
    assert "refusing %s" % renamed.name in message, message
    assert "it is ELF64 x86_64, the tag win_amd64 needs PE32+ x86_64" in message, message
    assert "its file name says another Python or system than the tag" in message, message
    assert not (tmp_path / "zips").exists() or not list((tmp_path / "zips").glob("*extension*")), "no zip may be made"


def test_a_wheel_of_another_python_is_refused(tmp_path):
    wheel = build_wheel()
    other = "cp313" if TAG != "cp313" else "cp311"
    renamed = tmp_path / wheel.name.replace(TAG, other)
    shutil.copy(wheel, renamed)
    result = package(tmp_path / "zips", renamed)
    assert result.returncode != 0
    assert "refusing %s" % renamed.name in result.stderr, result.stderr
    assert "it was built for Python %s, the tag %s needs %s.%s" % (PYTHON, other, other[2], other[3:]) in result.stderr, \
        result.stderr


def test_the_extension_zips_are_byte_identical_from_run_to_run(packaged, input_wheels, tmp_path):
    # The same wheels packed again (a wheel built anew carries its own build time: the claim is the
    # packager's, that the same inputs give the same bytes).
    out, _, _ = packaged
    again = tmp_path / "again"
    result = package(again, *input_wheels)
    assert result.returncode == 0, result.stdout + result.stderr
    names = sorted(path.name for path in out.glob("*.zip"))
    assert names == sorted(path.name for path in again.glob("*.zip")) and len(names) == 4, names
    for name in names:
        assert (out / name).read_bytes() == (again / name).read_bytes(), name


def extension_zip(out, platform):
    return out / ("gauss_stylization-%s-extension-%s-%s.zip" % (VERSION, TAG, platform.replace("-", "_")))


def test_one_extension_zip_per_platform_with_its_own_wheel(packaged):
    out, stdout, wheels = packaged
    _, (first, last) = package_addon.blender_ranges(PYTHON, ADDON_MIN)
    for platform, wheel in wheels.items():
        path = extension_zip(out, platform)
        assert "extension zip (Blender %s, %s, validated): %s" % (
            package_addon.releases(first, last), platform.replace("-", "_"), path) in stdout
        with zipfile.ZipFile(path) as archive:
            names = archive.namelist()
            manifest = tomllib.loads(archive.read("blender_manifest.toml").decode())
        assert manifest["id"] == "gauss_stylization" and manifest["version"] == VERSION
        assert manifest["blender_version_min"] == "%d.%d.0" % first
        if last is None:
            assert "blender_version_max" not in manifest
        else:
            assert manifest["blender_version_max"] == "%d.%d.0" % (last[0], last[1] + 1)
        assert manifest["platforms"] == list(wheels)  # the source manifest lists every platform...
        assert sorted(manifest["wheels"]) == sorted("./wheels/" + name for name in wheels.values())
        # ...and Blender's build adds what this zip holds: its own platform and wheel only.
        assert manifest["build"]["generated"] == {"platforms": [platform], "wheels": ["./wheels/" + wheel]}
        assert [name for name in names if name.startswith("wheels/")] == ["wheels/" + wheel]
        assert ".pc2" in manifest["permissions"]["files"]  # bakes write .pc2 files
        assert {"__init__.py", "native.py", "core_facts.json", "README.txt", "blender_manifest.toml"} <= set(names)
        assert set(ADDON_SOURCES) <= set(names) and "run/session.py" in names  # the sub-packages too
        assert not [name for name in names if name.startswith("gauss_core")]  # the module comes as the wheel


def test_blenders_validator_accepts_each_zip_and_rejects_a_broken_one(packaged, tmp_path):
    out, _, wheels = packaged
    for platform in wheels:
        code, output = blender_ext_tool.run("validate", str(extension_zip(out, platform)))
        assert code == 0, output
    # The validator does reject: the same zip with a permission reason that ends in a full stop.
    broken = tmp_path / "broken.zip"
    with zipfile.ZipFile(extension_zip(out, "linux-x64")) as source, zipfile.ZipFile(broken, "w") as target:
        for item in source.infolist():
            data = source.read(item)
            if item.filename == "blender_manifest.toml":
                data = data.replace(b'point cache files"', b'point cache files."')
            target.writestr(item, data)
    code, output = blender_ext_tool.run("validate", str(broken))
    assert code != 0 and "files" in output, output


def test_classic_zips_per_wheel(packaged):
    out, stdout, wheels = packaged
    first, last = package_addon.blender_ranges(PYTHON, ADDON_MIN)[0]
    for platform in wheels:
        path = out / ("gauss_stylization-%s-addon-%s-%s.zip" % (VERSION, TAG, package_addon.PLATFORMS[platform]))
        assert str(path) in stdout
        with zipfile.ZipFile(path) as archive:
            names = archive.namelist()
            readme = archive.read("gauss_stylization/README.txt").decode()
        assert {name.split("/")[0] for name in names} == {"gauss_stylization"}  # one top-level folder
        modules = [name for name in names if name.startswith("gauss_stylization/gauss_core")]
        suffix = ".pyd" if platform.startswith("windows") else ".so"  # the module as each platform names it
        assert len(modules) == 1 and modules[0].endswith(suffix), modules
        assert "gauss_stylization/__init__.py" in names and "gauss_stylization/core_facts.json" in names
        assert {"gauss_stylization/" + name for name in ADDON_SOURCES} <= set(names)  # the sub-packages too
        assert not [name for name in names if name.endswith("blender_manifest.toml")]
        assert "official Blender %s" % package_addon.releases(first, last) in readme


def test_classic_zip_of_the_build_tree(tmp_path):
    result = subprocess.run([sys.executable, str(SCRIPT), str(BUILD), str(tmp_path)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    classic = sorted(tmp_path.glob("*-addon-%s-linux_x86_64.zip" % TAG))
    assert len(classic) == 1 and len(list(tmp_path.iterdir())) == 1, result.stdout  # no extension without wheels
    row = package_addon.BLENDER_FOR_PYTHON[PYTHON]
    with zipfile.ZipFile(classic[0]) as archive:
        readme = archive.read("gauss_stylization/README.txt").decode()
    first, last = package_addon.blender_ranges(PYTHON, tuple(package_addon.addon_info()["blender"][:2]))[0]
    assert "built for Python %s" % PYTHON in readme
    assert "official Blender %s" % package_addon.releases(first, last) in readme
    assert all(also in readme for also in row["also"])
    assert "a local build" in readme
    for other in package_addon.BLENDER_FOR_PYTHON:
        if other != PYTHON:
            assert "-cp%s-" % other.replace(".", "") in readme
