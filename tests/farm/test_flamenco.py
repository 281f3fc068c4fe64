"""The Flamenco job type farm/flamenco/gauss_bake.js: its syntax checked by node, compiled with stand-ins
for a Flamenco Manager's job compiler API (flamenco_compile.js), and its tasks' commands run here in
dependency order as a worker would run them (blender {blenderArgs} BLENDFILE ARGS, blenderArgs being the
Manager's default "-b -y"). No Flamenco Manager runs: docs/baking.md says so."""

import json
import subprocess

from conftest import FARM_CLI, HERE, OBJECT, REPO, SHOT_FRAMES, assert_same_bytes, blender, run

JOB_TYPE = REPO / "farm" / "flamenco" / "gauss_bake.js"
BLENDER_ARGS = ["-b", "-y"]  # Flamenco's default {blenderArgs} for the blender variable


def test_node_finds_no_syntax_error():
    run(["node", "--check", JOB_TYPE])


def _compile(settings):
    result = run(["node", HERE / "flamenco_compile.js", JOB_TYPE, json.dumps(settings)])
    return json.loads(result.stdout)


def _worker_argv(command):
    assert command["name"] == "blender-render" and command["parameters"]["exe"] == "{blender}"
    parameters = command["parameters"]
    assert parameters["exeArgs"] == "{blenderArgs}"
    return ([blender()] + BLENDER_ARGS + ["--factory-startup"] + parameters["argsBefore"]
            + [parameters["blendfile"]] + parameters["args"])


def test_the_compiled_job_run_task_by_task_merges_into_the_one_process_bake(shot, one_bake, tmp_path):
    out = tmp_path / "capsule.pc2"
    # Two chunks (each task starts Blender: CI's time), the second of two frames, which frameChunker
    # writes "47,48" as the Manager's does; Blender's "1..48" is a range Flamenco takes too.
    size = SHOT_FRAMES[1] - SHOT_FRAMES[0] - 1
    tasks = _compile({"frames": "%d..%d" % SHOT_FRAMES, "object": OBJECT, "chunk_size": size, "output": str(out),
                      "farm_cli": str(FARM_CLI), "blendfile": str(shot)})
    names = [task["name"] for task in tasks]
    assert names == ["bake-1-46", "bake-47,48", "merge"]
    assert tasks[-1]["dependencies"] == names[:-1] and all(not t["dependencies"] for t in tasks[:-1])
    assert all(task["type"] == "blender" and len(task["commands"]) == 1 for task in tasks)
    for task in list(reversed(tasks[:-1])) + tasks[-1:]:  # the bakes in any order, the merge last
        run(_worker_argv(task["commands"][0]))
    assert_same_bytes(out, one_bake)


def test_a_failing_task_fails(shot, tmp_path):
    """A worker sees a failed bake (an object not in the file) as a failed task: Blender exits non-zero."""
    tasks = _compile({"frames": "1-2", "object": "Nobody", "chunk_size": 2, "output": str(tmp_path / "x.pc2"),
                      "farm_cli": str(FARM_CLI), "blendfile": str(shot)})
    result = subprocess.run(_worker_argv(tasks[0]["commands"][0]), capture_output=True, text=True,
                            stdin=subprocess.DEVNULL, timeout=120)
    assert result.returncode != 0
    assert "No object 'Nobody'" in result.stderr


def test_frames_that_are_not_one_range_are_refused_at_submission(shot, tmp_path):
    """Chunks of "1-10,20-30" would not join into one cache: compileJob throws, which the Manager shows as
    the submission's error."""
    settings = {"frames": "1-10,20-30", "object": OBJECT, "chunk_size": 8, "output": str(tmp_path / "x.pc2"),
                "farm_cli": str(FARM_CLI), "blendfile": str(shot)}
    result = subprocess.run(["node", HERE / "flamenco_compile.js", JOB_TYPE, json.dumps(settings)],
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=60)
    assert result.returncode != 0
    assert 'Frames must be one range A-B (e.g. 1-240), got "1-10,20-30"' in result.stderr
