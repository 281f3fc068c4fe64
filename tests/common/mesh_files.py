"""Reading triangle meshes from OBJ and ASCII PLY files, for the tests and the quality matrix.

numpy only. Polygons are split into fans of triangles; OBJ faces are indexed by the position index
alone (a v/vt pair does not make a new vertex, so UV seams stay joined). Vertices no face uses are
kept, as Blender's PLY importer keeps them.
"""
import numpy as np


def read_obj(path):
    """(V (#V,3) float64, F (#F,3) int64) of an OBJ file."""
    V, F = [], []
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            V.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            idx = [int(p.split("/")[0]) for p in parts[1:]]
            idx = [i - 1 if i > 0 else len(V) + i for i in idx]  # negative: counted back from the last v
            F += [(idx[0], idx[i], idx[i + 1]) for i in range(1, len(idx) - 1)]
    return np.array(V, np.float64).reshape(-1, 3), np.array(F, dtype=np.int64).reshape(-1, 3)


def read_ply(path):
    """(V, F) of an ASCII PLY file: x, y, z of element vertex, the index list of element face."""
    with open(path) as f:
        if f.readline().strip() != "ply":
            raise ValueError(f"{path}: not a PLY file")
        elements = []  # [name, count, [property names]]
        fmt = None
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "format":
                fmt = words[1]
            elif words[0] == "element":
                elements.append([words[1], int(words[2]), []])
            elif words[0] == "property" and elements:
                elements[-1][2].append(words[-1])
            elif words[0] == "end_header":
                break
        if fmt != "ascii":
            raise ValueError(f"{path}: PLY format {fmt!r} is not read here (only ascii)")
        V, F = np.zeros((0, 3)), []
        for name, count, props in elements:
            rows = [f.readline().split() for _ in range(count)]
            if name == "vertex":
                columns = [props.index(axis) for axis in ("x", "y", "z")]
                V = np.array([[float(r[c]) for c in columns] for r in rows], np.float64).reshape(-1, 3)
            elif name == "face":
                for r in rows:
                    idx = [int(x) for x in r[1:1 + int(r[0])]]
                    F += [(idx[0], idx[i], idx[i + 1]) for i in range(1, len(idx) - 1)]
    return V, np.array(F, dtype=np.int64).reshape(-1, 3)


def read_mesh(path):
    """(V, F) of an .obj or .ply file."""
    suffix = str(path).lower().rsplit(".", 1)[-1]
    readers = {"obj": read_obj, "ply": read_ply}
    if suffix not in readers:
        raise ValueError(f"{path}: only .obj and .ply are read")
    return readers[suffix](path)
