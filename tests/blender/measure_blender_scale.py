"""What Blender itself costs per live tick on a sculpt-sized mesh (informational, no assertion):

    blender -b --factory-startup -P tests/blender/measure_blender_scale.py -- [--n 409] [--repeats 20]
    VENV/bin/python tests/blender/measure_blender_scale.py [--n 409]          (a bpy wheel's venv)

The mesh is cpp/bench/scale_mesh.py's generated sphere (n = 409: 1,003,688 vertices; 580: 2,018,402),
made in Blender from numpy arrays. Each figure is the median over REPEATS of one operation on the whole
mesh, alternating between two shapes so that every write changes every coordinate:
  foreach_set co:       mesh.vertices.foreach_set("co", buffer) from a preallocated float32 buffer
  position attribute:   mesh.attributes["position"].data.foreach_set("vector", buffer) (Blender 3.5+)
  update():             mesh.update() after a write (what the add-on calls; the depsgraph runs later)
  update_tag():         mesh.update_tag() after a write
  depsgraph:            the evaluated depsgraph's update() after a write and update() (copy-on-write)
  normals:              vertex normals read after a write (recomputed) minus read when up to date
                        (mesh.vertex_normals from 3.5 on, vertices' normal before)
  numpy bounds check:   buffer.min() and buffer.max(), as Session._stepped checks a result
Prints one line per figure, "blender-scale: NAME ms: X".
"""

import os
import statistics
import sys
import time

import bpy
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "cpp", "bench"))
from scale_mesh import cube_sphere  # noqa: E402


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    n, repeats = 409, 20
    while argv:
        flag, value = argv[0], argv[1]
        if flag == "--n":
            n = int(value)
        elif flag == "--repeats":
            repeats = int(value)
        else:
            raise SystemExit("unknown argument %s" % flag)
        argv = argv[2:]
    return n, repeats


def make_mesh(V, F):
    mesh = bpy.data.meshes.new("scale")
    mesh.vertices.add(len(V))
    mesh.vertices.foreach_set("co", V.astype(np.float32).ravel())
    mesh.loops.add(3 * len(F))
    mesh.loops.foreach_set("vertex_index", F.ravel())
    mesh.polygons.add(len(F))
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * len(F), 3, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):  # read-only from 4.0 on (derived from loop_start)
        mesh.polygons.foreach_set("loop_total", np.full(len(F), 3, np.int32))
    mesh.update(calc_edges=True)
    obj = bpy.data.objects.new("scale", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    return obj


def median_ms(repeats, before, action):
    """Median ms of ``action(i)`` over ``repeats`` rounds, each after ``before(i)`` (untimed)."""
    times = []
    for i in range(repeats):
        before(i)
        start = time.perf_counter()
        action(i)
        times.append((time.perf_counter() - start) * 1000.0)
    return statistics.median(times)


def main():
    n, repeats = arguments()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    V, F = cube_sphere(n)
    obj = make_mesh(V, F)
    mesh = obj.data
    shapes = [V.astype(np.float32).ravel(), (V * 1.01).astype(np.float32).ravel()]
    normals = np.empty(3 * len(V), np.float32)
    print("blender-scale: Blender %s, %d vertices, %d faces, %d threads" % (
        bpy.app.version_string, len(mesh.vertices), len(mesh.polygons), os.cpu_count()))

    def write(i):
        mesh.vertices.foreach_set("co", shapes[i % 2])

    def write_and_update(i):
        write(i)
        mesh.update()

    def nothing(i):
        pass

    def read_normals(i):
        if hasattr(mesh, "vertex_normals"):  # 3.5 and later: one copy of the normals' array
            mesh.vertex_normals.foreach_get("vector", normals)
        else:
            mesh.vertices.foreach_get("normal", normals)

    depsgraph = bpy.context.evaluated_depsgraph_get()
    figures = [("foreach_set co", nothing, write)]
    if bpy.app.version >= (3, 5, 0):
        position = mesh.attributes["position"].data
        figures.append(("position attribute", nothing, lambda i: position.foreach_set("vector", shapes[i % 2])))
    figures += [
        ("update()", write, lambda i: mesh.update()),
        ("update_tag()", write, lambda i: mesh.update_tag()),
        ("depsgraph", write_and_update, lambda i: depsgraph.update()),
        ("normals (read after a write)", write_and_update, read_normals),
        ("normals (read, up to date)", nothing, read_normals),
        ("numpy bounds check", nothing, lambda i: (shapes[0].min(), shapes[0].max())),
    ]
    results = {}
    for name, before, action in figures:
        results[name] = median_ms(repeats, before, action)
        print("blender-scale: %s ms: %.2f" % (name, results[name]), flush=True)
    print("blender-scale: normals ms: %.2f" % (results["normals (read after a write)"]
                                                - results["normals (read, up to date)"]))


main()
