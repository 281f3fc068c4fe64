"""Meshes with large flat regions for Square Flat Regions (numpy only; tests/cpp/test_meshes.h builds
the same ones): a capped 32-sided cylinder, subdivided, and a pot whose flat lid is smaller than its
belly. `python3 tests/common/flat_meshes.py OUT_DIR` writes them as capped_cylinder.obj and pot.obj for
gauss_bench (docs/styles.md#square-flat-regions)."""
import math
import os
import sys

import numpy as np


def revolve(profile, sides, disk_rings):
    """A surface of revolution about z: profile (r, z) from bottom to top; an end at r == 0 is a pole,
    an end at r > 0 is closed by a flat disk of disk_rings rings. Outward normals. (V float64, F int64)."""
    rings = []
    if profile[0][0] > 0:
        rings += [(profile[0][0] * k / disk_rings, profile[0][1]) for k in range(disk_rings)]
    rings += list(profile)
    if profile[-1][0] > 0:
        rings += [(profile[-1][0] * k / disk_rings, profile[-1][1]) for k in reversed(range(disk_rings))]
    V, start = [], []
    for r, z in rings:
        start.append(len(V))
        for j in range(sides if r > 0 else 1):
            a = 2 * math.pi * j / sides
            V.append((r * math.cos(a), r * math.sin(a), z))
    F = []
    for i in range(len(rings) - 1):
        pole_a, pole_b = rings[i][0] == 0, rings[i + 1][0] == 0
        for j in range(sides):
            k = (j + 1) % sides
            a0, a1 = start[i] + (0 if pole_a else j), start[i] + (0 if pole_a else k)
            b0, b1 = start[i + 1] + (0 if pole_b else j), start[i + 1] + (0 if pole_b else k)
            if not pole_a:
                F.append((a0, a1, b1))
            if not pole_b:
                F.append((a0, b1, b0))
    return np.array(V, dtype=np.float64), np.array(F, dtype=np.int64)


def capped_cylinder():
    """Radius 1, height 2, 32 sides, 16 rows, caps of 8 rings."""
    return revolve([(1.0, -1.0 + 2.0 * i / 16) for i in range(17)], 32, 8)


def pot():
    """A round belly (radius 1.2) closed at the bottom, an upright neck of radius 0.72 and a flat lid."""
    top = math.acos(-0.8)
    profile = [(1.2 * math.sin(top * i / 20), -0.1 - math.cos(top * i / 20)) for i in range(21)]
    profile += [(1.2 * 0.6, 0.7 + 0.2 * i / 3) for i in range(1, 4)]
    return revolve(profile, 32, 6)


def write_obj(path, V, F):
    with open(path, "w") as out:
        out.writelines("v %.17g %.17g %.17g\n" % tuple(v) for v in V)
        out.writelines("f %d %d %d\n" % tuple(f + 1) for f in F)


if __name__ == "__main__":
    folder = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(folder, exist_ok=True)
    for name, make in (("capped_cylinder", capped_cylinder), ("pot", pot)):
        write_obj(os.path.join(folder, name + ".obj"), *make())
        print(os.path.join(folder, name + ".obj"))
