"""Measures the farm jobs for docs/performance.md ("On a farm"):

    /usr/bin/python3 tests/farm/measure_farm.py bake [--frames 240] [--chunks 4] [--mesh bunny/bun_zipper_35947.obj]
        [--no-slurm]
    /usr/bin/python3 tests/farm/measure_farm.py batch [--files 20]

bake: a shot of the mesh bent by an armature (make_shot.py, Warm Start off) baked by one Blender process,
then by a single-node Slurm cluster on this machine (slurm_cluster.py) as CHUNKS array tasks plus the
merge (farm/slurm/submit.sh); prints both wall times, the CPU-time model's o and t (chunks of 1 and 11
frames) against the one process's CPU time, the per-chunk overhead (a chunk's wall time less
its frames' time: Blender's start, loading the .blend, registering the add-on) and the time per frame,
and checks that the merged cache is the one-process bake byte for byte.
batch: farm_cli.py batch over every .obj of ../shared/meshes, the shot .blend files it makes and the
.ply (skipped: not a supported file), FILES in all, with a Cube preset; prints the wall time and each
file's line. Environment: GAUSS_BUILD_DIR (default <repo>/build).
"""

import argparse
import json
import os
import pathlib
import re
import resource
import subprocess
import sys
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[1]
MESHES = REPO.parent / "shared" / "meshes"
BUILD = pathlib.Path(os.environ.get("GAUSS_BUILD_DIR", REPO / "build")).resolve()
FARM_CLI = BUILD / "addon" / "gauss_stylization" / "bake" / "farm_cli.py"
sys.path.insert(0, str(HERE))
from slurm_cluster import Cluster  # noqa: E402


def _children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(argv, ok=(0,), **options):
    """(result, wall seconds); the CPU seconds (user + sys) of the run are in run.cpu afterwards."""
    start, cpu = time.perf_counter(), _children_cpu()
    result = subprocess.run([str(a) for a in argv], capture_output=True, text=True, stdin=subprocess.DEVNULL,
                            **options)
    wall = time.perf_counter() - start
    run.cpu = _children_cpu() - cpu
    if result.returncode not in ok:
        sys.exit("%s failed (%d):\n%s\n%s" % (argv, result.returncode, result.stdout[-3000:], result.stderr[-3000:]))
    return result, wall


def make_shot(folder, frames, mesh=None, name="shot"):
    blend = folder / ("%s.blend" % name)
    run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "-P", HERE / "make_shot.py", "--",
         BUILD, blend, "--frames", "1-%d" % frames] + (["--mesh", MESHES / mesh] if mesh else []))
    return blend


def bake_time(log):
    """Seconds of the frames themselves: the 'wrote ...: N frames in S s' line of a bake."""
    return float(re.search(r"gauss_bake: wrote .*: \d+ frames in ([\d.]+) s", log).group(1))


def measure_bake(args):
    work = pathlib.Path(tempfile.mkdtemp(prefix="gauss-farm-bench-"))
    blend = make_shot(work, args.frames, args.mesh)
    print("shot: %s, %d frames" % (args.mesh, args.frames), flush=True)
    one = work / "one.pc2"
    result, one_wall = run(["blender", "-b", blend, "--factory-startup", "--python-exit-code", "1", "-P", FARM_CLI,
                            "--", "bake", "--object", "Shot", "--frames", "1-%d" % args.frames, "--out", one])
    one_frames, one_cpu = bake_time(result.stdout), run.cpu
    print("one process: %.1f s wall, %.1f s of frames (%.3f s per frame), overhead %.1f s; %.1f s of CPU"
          % (one_wall, one_frames, one_frames / args.frames, one_wall - one_frames, one_cpu), flush=True)
    model_check(blend, args.frames, one_cpu, work)
    if args.no_slurm:
        return
    with Cluster(work / "slurm", cpus=2) as cluster:
        out = work / "farm" / "shot.pc2"
        start = time.perf_counter()
        submitted, _ = run(["bash", REPO / "farm" / "slurm" / "submit.sh", "--blend", blend, "--object", "Shot",
                            "--frames", "1-%d" % args.frames, "--chunks", args.chunks, "--out", out,
                            "--farm-cli", FARM_CLI, "--blender-args", "--factory-startup"], env=cluster.env)
        while True:
            queue = subprocess.run(["squeue", "-h"], capture_output=True, text=True, env=cluster.env).stdout
            if not queue.strip():
                break
            time.sleep(1.0)
        farm_wall = time.perf_counter() - start
    logs = sorted((work / "farm").glob("*.chunks/bake_*.log"))
    frames_time = [bake_time(path.read_text()) for path in logs]
    merge_log = next((work / "farm").glob("*.chunks/merge_*.log")).read_text()
    same = out.read_bytes() == one.read_bytes()
    print("slurm, %d chunks on 2 cores: %.1f s wall (submit to merged), chunks' frames %s s; merged = one "
          "process byte for byte: %s" % (args.chunks, farm_wall, ", ".join("%.1f" % t for t in frames_time), same))
    print(submitted.stdout.strip())
    print(merge_log.strip().splitlines()[-1])
    if not same:
        sys.exit("the merged cache differs from the one-process bake")


def model_check(blend, frames, one_cpu, work):
    """The CPU-time model of docs/performance.md: o (Blender's start, the .blend, the add-on) and t (a
    frame) from chunks of 1 and 11 frames, and what they predict for the one-process bake."""
    run(["blender", "-b", "--factory-startup", "--python-expr", "pass"])
    empty = run.cpu
    cpu = {}
    for count in (1, 11):
        run(["blender", "-b", blend, "--factory-startup", "--python-exit-code", "1", "-P", FARM_CLI, "--", "bake",
             "--object", "Shot", "--frames", "1-%d" % count, "--out", work / ("model_%d.pc2" % count)])
        cpu[count] = run.cpu
    t = (cpu[11] - cpu[1]) / 10.0
    o = cpu[1] - t
    print("CPU: empty Blender %.1f s, a chunk of 1 frame %.1f s, of 11 frames %.1f s -> t = %.2f s a frame, "
          "o = %.1f s a chunk; predicted for one process o + %d t = %.1f s, measured %.1f s"
          % (empty, cpu[1], cpu[11], t, o, frames, o + frames * t, one_cpu), flush=True)


def measure_batch(args):
    work = pathlib.Path(tempfile.mkdtemp(prefix="gauss-batch-bench-"))
    inputs = sorted(str(path) for path in MESHES.rglob("*.obj")) + sorted(str(p) for p in MESHES.rglob("*.ply"))
    shots = 0
    while len(inputs) < args.files:
        shots += 1
        inputs.append(str(make_shot(work, 3, name="shot%d" % shots)))
    inputs = inputs[:args.files]
    preset = work / "preset.json"
    preset.write_text(json.dumps({"lam": 2.0, "iterations": 20, "styles": [{"preset": "CUBE"}]}))
    result, wall = run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "-P", FARM_CLI, "--",
                        "batch"] + inputs + ["--preset", preset, "--out-dir", work / "out"], ok=(0, 3))
    for line in result.stdout.splitlines():
        if line.startswith("gauss_bake: file") or line.startswith("gauss_bake: batch"):
            print(line.replace(str(MESHES) + "/", "").replace(str(work) + "/", ""))
    print("batch of %d files: %.1f s wall (one Blender process)" % (len(inputs), wall))


def main():
    parser = argparse.ArgumentParser()
    jobs = parser.add_subparsers(dest="job", required=True)
    bake = jobs.add_parser("bake")
    bake.add_argument("--frames", type=int, default=240)
    bake.add_argument("--chunks", type=int, default=4)
    bake.add_argument("--mesh", default="bunny/bun_zipper_35947.obj")
    bake.add_argument("--no-slurm", action="store_true", help="only the one process and the CPU-time model")
    batch = jobs.add_parser("batch")
    batch.add_argument("--files", type=int, default=20)
    args = parser.parse_args()
    (measure_bake if args.job == "bake" else measure_batch)(args)


if __name__ == "__main__":
    main()
