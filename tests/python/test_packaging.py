"""scripts/package_addon.py: the Blender range of each zip derives from the Python the module was built for."""
import subprocess
import sys
import tomllib
import zipfile

import pytest

from conftest import BUILD, REPO

sys.path.insert(0, str(REPO / "scripts"))
import package_addon  # noqa: E402

ADDON_MIN = (3, 4)  # an add-on that needs Blender 3.4 or later


def test_blender_ranges_follow_the_python_version():
    assert package_addon.blender_ranges("3.10", ADDON_MIN) == (((3, 4), (4, 0)), None)  # no extension Blender
    assert package_addon.blender_ranges("3.11", ADDON_MIN) == (((4, 1), (5, 0)), ((4, 2), (5, 0)))
    assert package_addon.blender_ranges("3.13", ADDON_MIN) == (((5, 1), (5, 1)), ((5, 1), (5, 1)))
    with pytest.raises(SystemExit, match="no Blender release runs"):
        package_addon.blender_ranges("3.12", ADDON_MIN)


@pytest.mark.parametrize("python, first, first_unsupported",
                         [("3.11", "4.2.0", "5.1.0"), ("3.13", "5.1.0", "5.2.0")])
def test_manifest_range(python, first, first_unsupported):
    extension_range = package_addon.blender_ranges(python, ADDON_MIN)[1]
    manifest = tomllib.loads(package_addon.manifest_text("1.2.3", python, extension_range))
    assert (manifest["blender_version_min"], manifest["blender_version_max"]) == (first, first_unsupported)


def test_zips_name_their_python_and_blender_range(tmp_path):
    script = REPO / "scripts" / "package_addon.py"
    result = subprocess.run([sys.executable, str(script), str(BUILD), str(tmp_path)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    python = "%d.%d" % sys.version_info[:2]  # the build's Python: the one running these tests
    tag = "cp%d%d" % sys.version_info[:2]
    classic = sorted(tmp_path.glob("*-addon-%s-linux_x86_64.zip" % tag))
    extension = sorted(tmp_path.glob("*-extension-%s-linux_x86_64.zip" % tag))
    assert len(classic) == 1 and len(extension) == (0 if python == "3.10" else 1), result.stdout
    row = package_addon.BLENDER_FOR_PYTHON[python]
    with zipfile.ZipFile(classic[0]) as archive:
        readme = archive.read("gauss_stylization/README.txt").decode()
    first, last = package_addon.blender_ranges(python, tuple(package_addon.addon_info()["blender"][:2]))[0]
    assert "built for Python %s" % python in readme
    assert "official Blender %s" % package_addon.releases(first, last) in readme
    assert all(also in readme for also in row["also"])
    assert "It needs glibc 2." in readme
    for other in package_addon.BLENDER_FOR_PYTHON:
        if other != python:
            assert "-cp%s-linux_x86_64.zip" % other.replace(".", "") in readme
    if extension:
        with zipfile.ZipFile(extension[0]) as archive:
            assert "Python %s" % python in archive.read("README.txt").decode()
            assert "blender_version_max" in tomllib.loads(archive.read("blender_manifest.toml").decode())
