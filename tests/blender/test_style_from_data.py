"""Styles from data: From Object (a Custom style from an example's face directions) and
Auto Orient (the rotation under which the mesh already fits the active style best)."""

import bmesh
import bpy
import numpy as np
import pytest
from mathutils import Euler, Matrix

import helpers

OCTANTS = np.array([[x, y, z] for x in (1, -1) for y in (1, -1) for z in (1, -1)], float) / np.sqrt(3)


def _rotation(degrees):
    return np.array(Euler(np.radians(degrees), 'XYZ').to_matrix())


def _cube(name="Example", size=2.0):
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=size)
    return helpers.object_from_bmesh(bm, name)


def _mesh(name, vertices, faces):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in vertices], [], [tuple(f) for f in faces])
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _octahedron(name="Octahedron"):
    axes = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = []
    for x in (0, 1):
        for y in (2, 3):
            for z in (4, 5):
                corner = [x, y, z]
                # Outward: counter-clockwise seen from the octant the face looks into.
                sign = np.sign(np.dot(np.cross(np.subtract(axes[y], axes[x]), np.subtract(axes[z], axes[x])),
                                      np.add(np.add(axes[x], axes[y]), axes[z])))
                faces.append(corner if sign > 0 else corner[::-1])
    return _mesh(name, axes, faces)


def _facets(name, normals, size=0.2):
    """One small triangle per normal (its face normal), apart from the others: a mesh whose
    face directions are exactly ``normals``, all with the same area."""
    vertices, faces = [], []
    for k, n in enumerate(np.asarray(normals, float)):
        n = n / np.linalg.norm(n)
        u = np.cross(n, [1, 0, 0] if abs(n[0]) < 0.9 else [0, 1, 0])
        u /= np.linalg.norm(u)
        v = np.cross(n, u)
        centre = 3.0 * n
        vertices += [centre, centre + size * u, centre + size * v]
        faces.append((3 * k, 3 * k + 1, 3 * k + 2))
    return _mesh(name, vertices, faces)


def _from_object(target, source, **options):
    helpers.activate(target)
    return bpy.ops.object.gauss_style_from_object(source=source.name, **options)


def _custom_normals(obj):
    settings = obj.gauss_stylization
    slot = settings.styles[settings.active_style_index]
    assert slot.preset == 'CUSTOM'
    return np.array(slot.custom_normal_list())


def _same_directions(found, expected, degrees=1e-4):
    """Every direction of one set is within ``degrees`` of one of the other, both ways, one to one."""
    found = found / np.linalg.norm(found, axis=1)[:, None]
    expected = expected / np.linalg.norm(expected, axis=1)[:, None]
    cosine = found @ expected.T
    limit = np.cos(np.radians(degrees))
    return (len(found) == len(expected) and (cosine.max(axis=1) >= limit).all()
            and (cosine.max(axis=0) >= limit).all())


# -- From Object ---------------------------------------------------------------------

def test_a_cube_gives_exactly_its_six_axis_directions():
    example = _cube()
    target = helpers.suzanne(levels=0)
    assert _from_object(target, example) == {'FINISHED'}
    settings = target.gauss_stylization
    assert len(settings.styles) == 1 and settings.active_style_index == 0
    assert settings.styles[0].name == "From Example"
    assert _same_directions(_custom_normals(target), helpers.AXES)


def test_an_octahedron_gives_its_eight_directions():
    example = _octahedron()
    target = helpers.suzanne(levels=0)
    helpers.add_slot(target, 'CUBE')
    assert _from_object(target, example) == {'FINISHED'}
    assert target.gauss_stylization.active_style_index == 1  # added after the Cube slot, made active
    assert _same_directions(_custom_normals(target), OCTANTS)


def test_a_low_poly_example_gives_its_facet_normals():
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1)  # 20 facets
    example = bpy.context.active_object
    mesh = example.data
    expected = np.array([p.normal for p in mesh.polygons])
    target = helpers.suzanne(levels=0)
    assert _from_object(target, example) == {'FINISHED'}
    assert _same_directions(_custom_normals(target), expected, degrees=1e-3)
    # A prism whose sides are made of many quads: one direction per flat side.
    bpy.ops.mesh.primitive_cylinder_add(vertices=6)
    prism = bpy.context.active_object
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.subdivide(number_cuts=3)
    bpy.ops.object.mode_set(mode='OBJECT')
    flat_sides = np.unique(np.round([p.normal for p in prism.data.polygons], 5), axis=0)
    assert len(prism.data.polygons) > 50 and len(flat_sides) == 8
    assert _from_object(target, prism) == {'FINISHED'}
    assert _same_directions(_custom_normals(target), flat_sides, degrees=1e-3)


def test_directions_are_turned_by_the_two_objects_rotations():
    example = _cube()
    example.rotation_euler = np.radians((0.0, 0.0, 30.0))
    target = helpers.suzanne(levels=0)
    target.rotation_euler = np.radians((0.0, 0.0, 10.0))
    target.scale = (2.0, 1.0, 1.0)  # scale plays no part
    bpy.context.view_layer.update()
    assert _from_object(target, example) == {'FINISHED'}
    # The example's axes as the target sees them: turned by 30 - 10 = 20 degrees about Z.
    assert _same_directions(_custom_normals(target), helpers.AXES @ _rotation((0, 0, 20)).T, degrees=1e-3)


def test_small_clusters_are_dropped_and_the_largest_kept():
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=2.0)
    bm.verts.ensure_lookup_table()
    # A chamfer on one corner: a facet of about 0.02% of the area.
    bmesh.ops.bevel(bm, geom=[bm.verts[0]], offset=0.05, segments=1, affect='VERTICES')
    chamfered = helpers.object_from_bmesh(bm, "Chamfered")
    target = helpers.suzanne(levels=0)
    assert _from_object(target, chamfered) == {'FINISHED'}
    assert _same_directions(_custom_normals(target), helpers.AXES, degrees=1.0)
    # Of a cube with one side stretched, max_directions=2 keeps the two largest sides' directions.
    stretched = _cube("Slab")
    stretched.data.transform(Matrix.Diagonal((3.0, 3.0, 0.2, 1.0)))
    assert _from_object(target, stretched, max_directions=2) == {'FINISHED'}
    assert _same_directions(_custom_normals(target), np.array([(0, 0, 1), (0, 0, -1)]))


def test_from_object_refuses_what_has_no_directions():
    target = helpers.suzanne(levels=0)
    with pytest.raises(RuntimeError, match="there is no object 'Nothing'"):
        bpy.ops.object.gauss_style_from_object(source="Nothing")
    empty = bpy.data.objects.new("Empty", None)
    bpy.context.scene.collection.objects.link(empty)
    helpers.activate(target)
    with pytest.raises(RuntimeError, match="'Empty' is not a mesh"):
        bpy.ops.object.gauss_style_from_object(source="Empty")
    edges = _mesh("Wire", [(0, 0, 0), (1, 0, 0)], [])
    with pytest.raises(RuntimeError, match="no faces with area"):
        _from_object(target, edges)
    assert len(target.gauss_stylization.styles) == 0  # nothing was added


def test_a_style_from_a_cube_stylizes_like_the_cube_preset():
    example = _cube()
    target = helpers.suzanne(levels=1)
    assert _from_object(target, example) == {'FINISHED'}
    assert helpers.stylize(60, lam=8.0) == {'FINISHED'}
    assert helpers.aligned_share(target, helpers.AXES) > 0.5


# -- Auto Orient ---------------------------------------------------------------------

def _orientation(slot):
    return np.array(slot.orientation.to_matrix())


def _angle(a, b=np.eye(3)):
    return np.degrees(np.arccos(np.clip((np.trace(a @ b.T) - 1) / 2, -1, 1)))


@pytest.mark.parametrize("degrees", [(20, 30, 10), (-35, 5, 12), (0, 0, 40), (3, -2, 1)])
def test_a_rotated_cube_gets_its_rotation_back(degrees):
    obj = _cube("Turned")
    turn = _rotation(degrees)
    obj.data.transform(Matrix(turn.tolist()).to_4x4())
    slot = helpers.add_slot(obj, 'CUBE')
    assert bpy.ops.object.gauss_style_auto_orient() == {'FINISHED'}
    assert _angle(_orientation(slot), turn) < 1.0


def test_a_high_sigma_still_finds_the_rotation():
    """At sigma 1000 g's bumps are 2 degrees wide, far narrower than the search grid."""
    obj = _cube("Turned")
    turn = _rotation((20, 30, 10))
    obj.data.transform(Matrix(turn.tolist()).to_4x4())
    slot = helpers.add_slot(obj, 'CUBE', sigma=1000.0)
    assert bpy.ops.object.gauss_style_auto_orient() == {'FINISHED'}
    assert _angle(_orientation(slot), turn) < 1.0


def test_a_cube_turned_further_gets_the_nearest_equivalent_rotation():
    obj = _cube("Turned")
    turn = _rotation((50, -10, 70))  # 88 degrees; a cube looks the same turned by 90 about its axes
    obj.data.transform(Matrix(turn.tolist()).to_4x4())
    slot = helpers.add_slot(obj, 'CUBE')
    assert bpy.ops.object.gauss_style_auto_orient() == {'FINISHED'}
    found = _orientation(slot)
    assert _angle(found) < _angle(turn) - 10.0
    # ... and it is one of the 24 rotations that map the cube's face directions onto themselves.
    assert _same_directions(helpers.AXES @ found.T, helpers.AXES @ turn.T, degrees=1.0)


def test_an_axis_aligned_cube_keeps_no_rotation():
    obj = _cube("Aligned")
    slot = helpers.add_slot(obj, 'CUBE', orientation=(0.3, 0.2, 0.1))
    assert bpy.ops.object.gauss_style_auto_orient() == {'FINISHED'}
    assert tuple(slot.orientation) == (0.0, 0.0, 0.0)


def test_a_rotated_tetrahedron_gets_its_rotation_back(addon):
    gauss_core = addon.native.core()
    normals = gauss_core.Style.preset("tetrahedron").normals
    # The regular tetrahedron whose face normals these are: vertex k is opposite face k.
    vertices = -np.asarray(normals)
    faces = [[j for j in range(4) if j != k] for k in range(4)]
    faces = [f if np.dot(np.cross(vertices[f[1]] - vertices[f[0]], vertices[f[2]] - vertices[f[0]]),
                         normals[k]) > 0 else f[::-1] for k, f in enumerate(faces)]
    turn = _rotation((20, 30, 10))
    obj = helpers.activate(_mesh("Tetrahedron", vertices @ turn.T, faces))
    slot = helpers.add_slot(obj, 'TETRAHEDRON')
    assert bpy.ops.object.gauss_style_auto_orient() == {'FINISHED'}
    assert _angle(_orientation(slot), turn) < 1.0


def _style_directions(gauss_core, preset):
    """Directions a style prefers: its normals, and points around each of its rings."""
    style = gauss_core.Style.preset(preset)
    found = [np.asarray(style.normals)]
    axis = np.asarray(style.axis, float)
    side = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
    side /= np.linalg.norm(side)
    for offset in style.ring_offsets:
        angles = np.radians(np.arange(0, 360, 15))
        ring = (np.outer(np.cos(angles), side) + np.outer(np.sin(angles), np.cross(axis, side)))
        found.append(offset * axis + np.sqrt(1 - offset ** 2) * ring)
    return np.concatenate(found)


@pytest.mark.parametrize("preset", ['CUBE', 'TETRAHEDRON', 'OCTAHEDRON', 'DODECAHEDRON', 'ICOSAHEDRON',
                                    'SQUARE_PYRAMID', 'TRUNCATED_PYRAMID', 'TRIANGULAR_PRISM',
                                    'HEXAGONAL_PRISM', 'PLANE', 'CYLINDER', 'CONE', 'DOUBLE_CONE', 'CUSTOM'])
def test_every_style_finds_a_rotation_as_good_as_the_true_one_and_no_larger(addon, preset):
    """Facets facing exactly the turned style's directions: the rotation found fits them as
    well as the turn that made them, and turns no more than it (symmetries may give a smaller one)."""
    gauss_core = addon.native.core()
    custom = [(0, 0, 1), (1, 0, 0.2), (-0.3, 0.8, 0.1), (0.2, -0.5, -0.9)]
    directions = np.array(custom, float) if preset == 'CUSTOM' else _style_directions(gauss_core, preset.lower())
    turn = _rotation((25, -15, 35))
    obj = helpers.activate(_facets("Facets", directions @ turn.T))
    slot = helpers.add_slot(obj, preset, custom_normals=custom if preset == 'CUSTOM' else [])
    assert bpy.ops.object.gauss_style_auto_orient() == {'FINISHED'}
    found = _orientation(slot)
    style = addon.styles.make_style(gauss_core, slot, rotation=np.eye(3))
    normals, areas = addon.sphere.surface.face_normals(obj)
    fit = addon.sphere.orientation.Fit(style, normals, areas)
    assert fit(found[None])[0] >= fit(turn[None])[0] - 1e-5
    assert _angle(found) <= _angle(turn) + 0.5


def test_auto_orient_needs_a_buildable_style():
    obj = helpers.suzanne(levels=0)
    with pytest.raises(RuntimeError, match="Add a style slot first"):
        bpy.ops.object.gauss_style_auto_orient()
    helpers.add_slot(obj, 'CUSTOM', name="Empty")
    with pytest.raises(RuntimeError, match="Style 'Empty' is set to Custom but has no normals"):
        bpy.ops.object.gauss_style_auto_orient()
