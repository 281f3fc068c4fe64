"""scripts/quality_matrix.py, the quality matrix: a run that breaks its threshold fails the check,
naming mesh, option and measure (so CI's --fast run is a check that can fail), a mesh the solver
refuses is a recorded error, and a crash costs one record, not the matrix."""
import json
import os
import subprocess
import sys

import numpy as np

from conftest import BUILD, REPO
from meshes import icosphere

sys.path.insert(0, str(REPO / "scripts" / "quality"))
import runner  # noqa: E402
import thresholds  # noqa: E402


def _write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines(f"v {x} {y} {z}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)


def _matrix(meshes, table, *extra):
    return subprocess.run([sys.executable, str(REPO / "scripts" / "quality_matrix.py"), "--options", "cube",
                           "--meshes", str(meshes), "--thresholds", str(table), *extra],
                          env=dict(os.environ, GAUSS_BUILD_DIR=str(BUILD)), capture_output=True, text=True,
                          timeout=600)


def test_a_run_that_breaks_a_doctored_threshold_fails_naming_mesh_option_and_measure(tmp_path):
    V, F = icosphere(2)
    (tmp_path / "meshes").mkdir()
    _write_obj(tmp_path / "meshes" / "egg.obj", V * [1.0, 1.3, 0.8], F)
    table = tmp_path / "thresholds.json"
    made = _matrix(tmp_path / "meshes", table, "--write-thresholds")  # checks the run against them, too
    assert made.returncode == 0 and "every run within its thresholds" in made.stdout, made.stderr
    cell = json.loads(table.read_text())["egg.obj"]["cube"]
    assert cell["finite_bounded"] and cell["must_converge"] and cell["max_new_pairs"] == 0

    table.write_text(json.dumps({"egg.obj": {"cube": dict(cell, min_share=1.0, max_new_pairs=-1)}}))
    doctored = _matrix(tmp_path / "meshes", table)
    assert doctored.returncode == 1
    assert "egg.obj / cube: min_share: share" in doctored.stderr
    assert "egg.obj / cube: max_new_pairs: 0 new crossing pairs > -1" in doctored.stderr


def test_a_mesh_the_solver_refuses_is_a_recorded_error_and_its_threshold_says_so(tmp_path):
    (tmp_path / "meshes").mkdir()
    _write_obj(tmp_path / "meshes" / "dangling.obj", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 3)])
    table = tmp_path / "thresholds.json"
    run = _matrix(tmp_path / "meshes", table, "--write-thresholds")
    assert run.returncode == 0, run.stderr
    assert "dangling.obj" in run.stdout and "ValueError: face 0 refers to vertex 3" in run.stdout
    assert json.loads(table.read_text()) == {"dangling.obj": {"cube": {"error": True}}}


def _record(**changes):
    record = {"mesh": "m.obj", "option": "cube +avoid", "steps": 40, "stopped": True, "converged": True, "held_back": False, "held_last": 0,
              "finite": True, "bounded": True, "share": 0.8, "new_pairs": 0}
    record.update(changes)
    return record


def test_every_measure_of_a_threshold_is_checked():
    table = {"m.obj": {"cube +avoid": thresholds.make(_record())}}
    assert thresholds.check([_record()], table) == []
    assert thresholds.check([_record(share=0.7)], table) == ["m.obj / cube +avoid: min_share: share 0.700 < 0.78"]
    assert "max_new_pairs: 3 new" in thresholds.check([_record(new_pairs=3)], table)[0]
    assert "finite_bounded: result not bounded" in thresholds.check([_record(bounded=False)], table)[0]
    assert "7 steps ran away" in thresholds.check([_record(runaway=7)], table)[0]
    assert "must_converge: stopped by the guard" in thresholds.check(
        [_record(held_last=12, held_back=True, converged=False)], table)[0]
    capped = _record(stopped=False, converged=False, steps=400)
    assert "must_converge: not within 400 steps" in thresholds.check([capped], table)[0]
    assert "expected a result" in thresholds.check([_record(error="ValueError: x")], table)[0]
    assert "crashed" in thresholds.check([{"mesh": "m.obj", "option": "cube +avoid", "crash": "exit -11"}], table)[0]
    missing = thresholds.check([_record(option="cube")], table)
    assert missing and "1 runs have no threshold (m.obj / cube)" in missing[0]


def test_a_worker_that_crashes_costs_one_record_and_the_mesh_goes_on(monkeypatch):
    crash_on = "cube +avoid"
    script = ("import json, os, signal, sys\n"
              "for name in sys.argv[1:]:\n"
              "    print(json.dumps({'start': name, 'vertices': 3, 'faces': 1, 'kind': 'closed'}), flush=True)\n"
              f"    if name == {crash_on!r}: os.kill(os.getpid(), signal.SIGSEGV)\n"
              "    print(json.dumps({'option': name, 'error': 'ValueError: fake'}), flush=True)\n")
    monkeypatch.setattr(runner, "_worker", lambda folder, mesh, names: subprocess.Popen(
        [sys.executable, "-c", script, *names], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
    records = runner.run_mesh("folder", "m.obj", ["cube", crash_on, "cubic"], log=lambda record: None)
    assert [r["option"] for r in records] == ["cube", crash_on, "cubic"]
    assert "exit code -11" in records[1]["crash"] and records[1]["kind"] == "closed"
    assert "error" in records[0] and "error" in records[2]


def test_new_pairs_slid_from_the_input_crossings_are_told_from_the_others():
    """A crossing the input had may slide on to the faces around it, step after step (the guard allows
    that); the matrix counts the new pairs in a crossing region that holds an input crossing apart, and
    only those: a pair in a region of its own began elsewhere."""
    sys.path.insert(0, str(BUILD / "python"))  # measure_run imports gauss_core
    import measure_run
    # A strip of triangles along x: face 2k = (k, k+1, k+100), face 2k+1 = (k+1, k+101, k+100).
    F = np.array([f for k in range(30) for f in ((k, k + 1, k + 100), (k + 1, k + 101, k + 100))])
    pairs_in = {(0, 40)}  # faces 0 and 40 (columns 0 and 20) crossed in the input
    near = {(1, 41), (2, 39)}  # each face shares a corner with a face of that pair
    far = {(5, 44)}  # face 5 (column 2) and face 44 (column 22) share no corner with faces 0 and 40
    chain = {(3, 41)}  # face 3 shares a corner with face 5, face 41 with face 40
    apart = {(10, 50)}  # faces 10 and 50 (columns 5 and 25) touch no crossing face
    slid = measure_run.slid_from_input_crossings
    assert slid(F, pairs_in, near) == 2
    assert slid(F, pairs_in, far) == 0 and slid(F, pairs_in, apart) == 0
    assert slid(F, pairs_in, far | chain) == 2  # the crossing slid on through face 3 to face 5
    assert slid(F, pairs_in, near | far | chain | apart) == 4
    assert slid(F, set(), near) == 0


def test_a_run_held_where_the_plain_run_crosses_is_listed_apart_from_the_failures():
    """The guard holding a run back where the same run without it passes through the surface is what it
    is for: listed as held at a contact, not among the failures. Held where the plain run crosses
    nowhere, it is a failure."""
    import report
    held = _record(converged=False, held_back=True, held_last=12, held_max=30, vertices=100, share=0.78)
    for plain_pairs, failing in ((61, False), (0, True)):
        records = [_record(option="cube", new_pairs=plain_pairs, share=0.8), held]
        guard = report.findings(records)["Avoid Self-Intersections"]
        apart = report.held_at_contacts(records)
        assert bool(guard) is failing and bool(apart) is not failing
        if failing:
            assert guard == ["m.obj / cube +avoid: the guard stopped the run where the plain run crosses nowhere "
                             "(12 vertices held back in its last step)"]
        else:
            assert apart == ["m.obj / cube +avoid: held (12 vertices in its last step) where the plain run makes 61 "
                             "crossing pairs; share -0.020 against it"]
    # Held and far below the plain run's share, it fails on the share whatever the plain run crossed.
    low = dict(held, share=0.5, kind="closed")
    guard = report.findings([_record(option="cube", new_pairs=61, share=0.8), low])["Avoid Self-Intersections"]
    assert guard == ["m.obj / cube +avoid: share 0.500, 0.300 below the plain run's (the criterion: within 0.05)"]
