"""A real single-node Slurm cluster (slurm_cluster.py) bakes the shot with farm/slurm/submit.sh: 4 chunks
as an array job, the merge after them (--dependency=afterok). The merged cache must be the one-process
bake byte for byte (Warm Start off), and the daemons must be gone afterwards. A cluster that does not
start fails the test with the reason."""

import re
import subprocess
import time

import pytest

from conftest import BAKE_TIMEOUT, CHUNKS, FARM_CLI, OBJECT, REPO, SHOT_FRAMES, assert_same_bytes, blender, run
from slurm_cluster import Cluster, ClusterError

SUBMIT = REPO / "farm" / "slurm" / "submit.sh"


def _job_state(cluster, job):
    result = subprocess.run(["scontrol", "-o", "show", "job", job], capture_output=True, text=True,
                            env=cluster.env, stdin=subprocess.DEVNULL, timeout=30)
    states = re.findall(r"JobState=(\S+)", result.stdout)
    return states


def _wait(cluster, jobs):
    """Wait until no job of ``jobs`` is pending or running; their final states."""
    deadline = time.monotonic() + BAKE_TIMEOUT
    while time.monotonic() < deadline:
        states = {job: _job_state(cluster, job) for job in jobs}
        if all(s and not set(s) & {"PENDING", "RUNNING", "CONFIGURING", "COMPLETING"} for s in states.values()):
            return states
        time.sleep(1.0)
    pytest.fail("the Slurm jobs did not end within %d s: %s" % (BAKE_TIMEOUT, states))


def test_a_slurm_array_bake_merged_is_the_one_process_bake(shot, one_bake, tmp_path):
    cluster = Cluster(tmp_path / "slurm", cpus=2)
    try:
        cluster.start()
    except ClusterError as exc:
        pytest.fail("the single-node Slurm cluster did not start: %s" % exc)
    try:
        out = tmp_path / "farm" / "capsule.pc2"
        submitted = run(["bash", SUBMIT, "--blend", shot, "--object", OBJECT,
                         "--frames", "%d-%d" % SHOT_FRAMES, "--chunks", CHUNKS, "--out", out,
                         "--farm-cli", FARM_CLI, "--blender", blender(), "--blender-args", "--factory-startup"],
                        env=cluster.env)
        jobs = dict(line.split() for line in submitted.stdout.split("\n") if line.strip())
        states = _wait(cluster, [jobs["array"], jobs["merge"]])
        logs = "\n".join(path.read_text(errors="replace") for path in sorted(out.parent.glob("*.chunks/*.log")))
        assert states[jobs["array"]] == ["COMPLETED"] * CHUNKS, (states, logs)
        assert states[jobs["merge"]] == ["COMPLETED"], (states, logs)
        chunks = sorted(out.parent.glob("*.chunks/chunk_*.pc2"))
        assert [c.name for c in chunks] == ["chunk_000001.pc2", "chunk_000013.pc2", "chunk_000025.pc2",
                                            "chunk_000037.pc2"]
        # Every chunk printed a line per frame it baked.
        assert len(re.findall(r"gauss_bake: frame \d+: \d+/12 ", logs)) == 48, logs
        assert_same_bytes(out, one_bake)
    finally:
        cluster.stop()
    assert cluster.running() == []
    for mark in (str(cluster.conf), cluster.socket):  # slurmctld and slurmd name the first, munged the second
        assert subprocess.run(["pgrep", "-f", mark], capture_output=True).stdout == b""


def test_a_cluster_that_cannot_start_fails_with_the_reason_and_leaves_no_daemon(tmp_path, monkeypatch):
    write_conf = Cluster._write_conf

    def broken_conf(cluster):
        write_conf(cluster)
        with open(cluster.conf, "a") as handle:
            handle.write("NoSuchSlurmOption=1\n")

    monkeypatch.setattr(Cluster, "_write_conf", broken_conf)
    cluster = Cluster(tmp_path / "slurm")
    with pytest.raises(ClusterError, match="slurmctld exited with status") as error:
        cluster.start()
    assert "NoSuchSlurmOption" in str(error.value)  # the daemon's own words
    assert cluster.running() == []  # munged and slurmd, started before slurmctld gave up, were stopped
    assert subprocess.run(["pgrep", "-f", cluster.socket], capture_output=True).stdout == b""
