""".github/workflows/release.yml cannot run here: actionlint checks it, and these tests check that it builds
what the packaging promises (the Pythons and platforms BLENDER_FOR_PYTHON and package_addon.PLATFORMS
name) by calling the project's own scripts rather than a second copy of the build."""
import os
import re
import subprocess
import sys
import tomllib

import pytest

from conftest import REPO
from wheel_build import tools_venv

sys.path.insert(0, str(REPO / "scripts"))
import blender_ext_tool  # noqa: E402
import package_addon  # noqa: E402

WORKFLOW = REPO / ".github" / "workflows" / "release.yml"
PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())


@pytest.fixture(scope="module")
def actionlint():
    return tools_venv() / "bin" / "actionlint"


def test_actionlint_passes(actionlint):
    result = subprocess.run([str(actionlint), "-no-color", str(WORKFLOW)], capture_output=True, text=True, cwd=REPO)
    assert result.returncode == 0, result.stdout + result.stderr


def test_actionlint_catches_a_broken_workflow(actionlint, tmp_path):
    broken = tmp_path / ".github" / "workflows" / "release.yml"
    broken.parent.mkdir(parents=True)
    broken.write_text(WORKFLOW.read_text().replace("needs: wheels", "needs: wheel"))  # an unknown job
    result = subprocess.run([str(actionlint), "-no-color", str(broken)], capture_output=True, text=True, cwd=tmp_path)
    assert result.returncode != 0 and "wheel" in result.stdout, result.stdout + result.stderr


def test_cibuildwheel_builds_every_python_a_blender_runs():
    selectors = PYPROJECT["tool"]["cibuildwheel"]["build"]
    assert sorted(selectors) == sorted("cp%s-*" % python.replace(".", "") for python in package_addon.BLENDER_FOR_PYTHON)


def test_the_workflow_builds_every_platform_the_extension_ships():
    text = WORKFLOW.read_text()
    wheel_platforms = re.findall(r"^\s*- platform: (\S+)$", text, re.M)
    blender_ext = blender_ext_tool.module()
    covered = sorted(p for tag in wheel_platforms for p in blender_ext.blender_platforms_from_wheel_platform(tag))
    assert covered == sorted(package_addon.PLATFORMS)
    assert "manylinux_2_28_x86_64" in wheel_platforms
    assert PYPROJECT["tool"]["cibuildwheel"]["manylinux-x86_64-image"] == "manylinux_2_28"


def test_the_workflow_calls_the_projects_scripts_and_pins():
    text = WORKFLOW.read_text()
    for command in ("bash scripts/install_deps.sh", "bash scripts/build.sh build",
                    "python3 scripts/package_addon.py build dist --wheels wheelhouse/*.whl",
                    "python -m cibuildwheel"):
        assert command in text, command
    # cibuildwheel's version is read from the one pin file the local tools venv is made from.
    assert "grep '^cibuildwheel==' packaging/tools-requirements.txt" in text
    pins = (REPO / "packaging" / "tools-requirements.txt").read_text()
    assert re.search(r"^cibuildwheel==\d+\.\d+\.\d+$", pins, re.M)


@pytest.mark.parametrize("platform, identifiers", [
    ("linux", ["manylinux_x86_64"]), ("windows", ["win_amd64"]), ("macos", ["macosx_x86_64", "macosx_arm64"])])
def test_cibuildwheel_reads_the_config_as_meant(platform, identifiers):
    # cibuildwheel itself (the pinned version) resolves pyproject.toml: every Python a Blender runs, on
    # every platform, and nothing else (requires-python or a skip pattern could drop some silently).
    result = subprocess.run([str(tools_venv() / "bin" / "cibuildwheel"), "--print-build-identifiers",
                             "--platform", platform], capture_output=True, text=True, cwd=REPO,
                            env={k: v for k, v in os.environ.items() if not k.startswith("CIBW_")})
    assert result.returncode == 0, result.stdout + result.stderr
    expected = ["cp%s-%s" % (python.replace(".", ""), identifier)
                for python in package_addon.BLENDER_FOR_PYTHON for identifier in identifiers]
    assert sorted(result.stdout.split()) == sorted(expected)


def test_pypi_publishing_is_trusted_optional_and_on_tags_only():
    text = WORKFLOW.read_text()
    job = text[text.index("\n  pypi:\n"):]
    assert "if: startsWith(github.ref, 'refs/tags/v') && vars.PUBLISH_TO_PYPI == 'true'" in job
    assert "id-token: write" in job and "pypa/gh-action-pypi-publish@v" in job
    assert "password" not in job and "secrets." not in job  # trusted publishing: no stored token
    # It uploads the wheels the package job put in the extension zips, and only those.
    assert "pattern: wheels-*" in job and "needs: [wheels, package]" in job
