"""The Open Job Description template farm/openjd/gauss_bake.yaml, run by openjd-cli (pinned in
packaging/farm-requirements.txt, in the farm venv scripts/install_deps.sh makes): the shot in 2 chunks of
24 frames (TASK_CHUNKING), then the merge; the merged cache must be the one-process bake byte for byte
(Warm Start off)."""

import pathlib
import re
import subprocess

import pytest

from conftest import FARM_CLI, OBJECT, REPO, SHOT_FRAMES, assert_same_bytes, blender, run

TEMPLATE = REPO / "farm" / "openjd" / "gauss_bake.yaml"


def _openjd():
    venv = subprocess.run(["bash", str(REPO / "scripts" / "install_deps.sh"), "--print-farm-venv"],
                          capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=900)
    program = pathlib.Path(venv.stdout.strip().splitlines()[-1] if venv.stdout.strip() else "") / "bin" / "openjd"
    if venv.returncode != 0 or not program.is_file():
        pytest.fail("no openjd in the farm venv (scripts/install_deps.sh):\n%s" % venv.stderr[-2000:])
    return program


def test_the_template_passes_openjd_check():
    result = run([_openjd(), "check", TEMPLATE])
    assert "passes validation" in result.stdout


def test_an_openjd_run_merged_is_the_one_process_bake(shot, one_bake, tmp_path):
    out = tmp_path / "capsule.pc2"
    size = (SHOT_FRAMES[1] - SHOT_FRAMES[0] + 1) // 2  # two chunks: each task starts Blender (CI's time)
    result = run([_openjd(), "run", TEMPLATE, "--step", "Merge", "--run-dependencies",
                  "-p", "BlendFile=%s" % shot, "-p", "ObjectName=%s" % OBJECT,
                  "-p", "Frames=%d-%d" % SHOT_FRAMES, "-p", "ChunkSize=%d" % size, "-p", "OutputFile=%s" % out,
                  "-p", "FarmCli=%s" % FARM_CLI, "-p", "BlenderExecutable=%s" % blender()], cwd=tmp_path)
    log = result.stdout + result.stderr
    chunks = sorted(p.name for p in (tmp_path / "capsule.pc2.chunks").glob("chunk_*.pc2"))
    assert chunks == ["chunk_1-24.pc2", "chunk_25-48.pc2"], log[-3000:]
    assert len(re.findall(r"gauss_bake: frame \d+: \d+/24 ", log)) == 48, log[-3000:]
    assert_same_bytes(out, one_bake)
