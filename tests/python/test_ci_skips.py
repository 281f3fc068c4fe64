"""tests/common/ci_skips.py: under CI=true a skip fails unless its reason is on the allow-list, and the
summary prints the skip count with the list."""
import os
import subprocess
import sys
import textwrap

import pytest

from conftest import REPO

SUITE = '''
import pytest

def test_runs():
    pass

def test_needs_a_file():
    pytest.skip("../shared/meshes not present")

@pytest.mark.skipif(True, reason="needs numpy 2 (scripts/test_numpy2.sh runs this file with it)")
def test_needs_numpy_2():
    pass
'''


def _run(tmp_path, **env):
    (tmp_path / "conftest.py").write_text(textwrap.dedent('''
        import sys
        sys.path.insert(0, %r)
        from ci_skips import pytest_runtest_makereport, pytest_terminal_summary
        ''' % str(REPO / "tests" / "common")))
    (tmp_path / "test_suite.py").write_text(SUITE)
    environment = {k: v for k, v in os.environ.items() if k not in ("CI", "GAUSS_RELEASE_WHEEL_TESTS")}
    environment.update(env)
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(tmp_path)],
                          cwd=tmp_path, env=environment, capture_output=True, text=True)


def test_outside_ci_a_skip_is_a_skip(tmp_path):
    run = _run(tmp_path)
    assert run.returncode == 0, run.stdout
    assert "1 passed, 2 skipped" in run.stdout
    assert "skipped: 2, 1 of them on the allow-list" in run.stdout


def test_under_ci_a_skip_not_on_the_list_fails_and_one_on_it_does_not(tmp_path):
    run = _run(tmp_path, CI="true")
    assert run.returncode == 1, run.stdout
    assert "1 failed, 1 passed, 1 skipped" in run.stdout
    assert "FAILED" in run.stdout and "test_needs_a_file" in run.stdout
    assert "not on the allow-list" in run.stdout
    assert "allow-list: the numpy 2 checks" in run.stdout  # the list is printed with the totals


def test_the_release_wheels_may_lack_the_shared_meshes(tmp_path):
    run = _run(tmp_path, CI="true", GAUSS_RELEASE_WHEEL_TESTS="1")
    assert run.returncode == 0, run.stdout
    assert "1 passed, 2 skipped" in run.stdout


@pytest.mark.parametrize("suite", ["tests/python", "tests/farm"])
def test_every_plain_pytest_suite_loads_the_plugin(suite):
    # Each suite's conftest.py must load it, or a skip there passes silently under CI=true; a run of the
    # conftest alone collects no test (nothing is imported but it) and still prints the plugin's totals.
    environment = {k: v for k, v in os.environ.items() if k != "CI"}
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                          str(REPO / suite / "conftest.py")], cwd=REPO, env=environment, capture_output=True, text=True)
    assert "skipped: 0, 0 of them on the allow-list" in run.stdout, run.stdout + run.stderr
