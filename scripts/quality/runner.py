"""Runs the quality matrix: every mesh file under a folder, each in a worker process (worker.py), and
collects the records. A worker that dies (a crash) costs one record, {"crash": ...}, for the run it was
in; the mesh's remaining options go on in a new worker.
"""
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# The --fast subset's meshes: small and medium ones of each kind (closed, with boundary, broken).
FAST_MESHES = (
    "small/cube_libigl_8.obj", "small/spot_triangulated_2930.obj", "bunny/bunny_npm_1839.obj",
    "bunny/bunny_cubicstylization_6172.obj",
    "boundary/cube_no_bottom_25.obj", "boundary/cat_head_131.obj", "boundary/hand_lowres_810.obj",
    "bad/degtri_sliding_zero_area.obj", "bad/fan3_nonmanifold_edge.obj",
)


def mesh_files(folder, fast):
    """Paths relative to `folder` of its .obj and .ply files (of FAST_MESHES if `fast`), smallest file
    first (a long run has the most meshes done early)."""
    found = sorted((os.path.relpath(os.path.join(d, f), folder) for d, _, files in os.walk(folder)
                    for f in files if f.lower().endswith((".obj", ".ply"))),
                   key=lambda m: (os.path.getsize(os.path.join(folder, m)), m))
    return [m for m in found if m in FAST_MESHES] if fast else found


def _worker(folder, mesh, names):
    return subprocess.Popen([sys.executable, os.path.join(HERE, "worker.py"), os.path.join(folder, mesh), *names],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def run_mesh(folder, mesh, names, log):
    """The records of options `names` on one mesh; `log(record)` is called as each one arrives."""
    records, remaining = [], list(names)
    while remaining:
        process = _worker(folder, mesh, remaining)
        started = None
        for line in process.stdout:
            if not line.startswith("{"):
                continue
            message = json.loads(line)
            if "start" in message:
                started = message
                continue
            message["mesh"] = mesh
            records.append(message)
            log(message)
            remaining.remove(message["option"])
            started = None
        stderr = process.stderr.read()
        process.wait()
        if process.returncode == 0 and not remaining:
            break
        name = started["start"] if started else remaining[0]
        tail = " | ".join(stderr.strip().splitlines()[-3:])
        record = {"mesh": mesh, "option": name, "crash": f"worker exit code {process.returncode}: {tail}"}
        if started:
            record.update({k: started[k] for k in ("vertices", "faces", "kind")})
        records.append(record)
        log(record)
        remaining.remove(name)
    return records


def run_matrix(folder, rows, fast, log, mesh_done=None):
    """All records of the options `rows` on the meshes of `folder`, and the wall time in seconds;
    `mesh_done(records, seconds, meshes left)` is called after each mesh."""
    start = time.monotonic()
    records, meshes = [], mesh_files(folder, fast)
    for i, mesh in enumerate(meshes):
        records += run_mesh(folder, mesh, [o.name for o in rows], log)
        if mesh_done:
            mesh_done(records, time.monotonic() - start, len(meshes) - i - 1)
    return records, time.monotonic() - start
