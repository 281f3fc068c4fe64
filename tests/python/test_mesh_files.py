"""tests/common/mesh_files.py, the mesh reader the tests and the quality matrix share: OBJ and ASCII PLY
give the same triangles, polygons become fans, and a file it cannot read is a clear error."""
import numpy as np
import pytest

from conftest import SHARED_MESHES
from mesh_files import read_mesh

PLY_QUAD = """ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
property float confidence
element face 1
property list uchar int vertex_indices
end_header
0 0 0 1
1 0 0 1
1 1 0 1
0 1 0 1
4 0 1 2 3
"""


def test_a_ply_polygon_becomes_a_fan_of_triangles(tmp_path):
    (tmp_path / "quad.ply").write_text(PLY_QUAD)
    V, F = read_mesh(tmp_path / "quad.ply")
    assert V.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    assert F.tolist() == [[0, 1, 2], [0, 2, 3]]


@pytest.mark.parametrize("name, text, message", [
    ("binary.ply", PLY_QUAD.replace("ascii", "binary_little_endian"), "only ascii"),
    ("not.ply", "solid\n", "not a PLY file"),
    ("mesh.stl", "solid\n", "only .obj and .ply"),
])
def test_a_file_it_cannot_read_is_a_clear_error(tmp_path, name, text, message):
    (tmp_path / name).write_text(text)
    with pytest.raises(ValueError, match=message):
        read_mesh(tmp_path / name)


def test_the_stanford_bunny_reads_the_same_from_its_ply_and_its_obj():
    """The same vertices (the OBJ rounded to 6 decimals) and faces; the OBJ export turned every face over."""
    ply = SHARED_MESHES / "bunny" / "bun_zipper_stanford_original.ply"
    obj = SHARED_MESHES / "bunny" / "bun_zipper_35947.obj"
    if not (ply.exists() and obj.exists()):
        pytest.skip("../shared/meshes not present")
    (Vp, Fp), (Vo, Fo) = read_mesh(ply), read_mesh(obj)
    assert Vp.shape == (35947, 3) and Fp.shape == (69451, 3)
    assert np.array_equal(Fp, Fo[:, ::-1]) and np.allclose(Vp, Vo, atol=1e-6)
