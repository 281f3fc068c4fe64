"""Use Modifiers (the evaluated mesh as input) and the outputs: Mesh, Shape Key, New Object.

Every output keeps everything the mesh holds besides the positions it writes:
UVs, colour attributes, custom split normals, materials, polygons, edges,
vertex groups and other attributes (compared bit for bit after the original
positions are written back, so custom normals, stored relative to the surface,
must come out exactly as they were).
"""

import bpy
import numpy as np
import pytest

import helpers
from mesh_layers import decorated_suzanne, differences, layers

STEPS = 10


def _stylized_object(addon, obj):
    """The object the last stylization of ``obj`` wrote to."""
    if obj.gauss_stylization.output == 'NEW_OBJECT':
        return bpy.data.objects[obj.name + addon.settings.schema.NEW_OBJECT_SUFFIX]
    return obj


@pytest.mark.parametrize("output, use_modifiers", [('MESH', False), ('MESH', True), ('SHAPE_KEY', False),
                                                   ('SHAPE_KEY', True), ('NEW_OBJECT', False),
                                                   ('NEW_OBJECT', True)])
def test_every_layer_survives_the_output(addon, output, use_modifiers):
    obj = decorated_suzanne()
    helpers.activate(obj)
    start, before = helpers.coords(obj), layers(obj)
    assert helpers.stylize(STEPS, output=output, use_modifiers=use_modifiers) == {'FINISHED'}
    written = _stylized_object(addon, obj)
    if output == 'SHAPE_KEY':
        key = obj.data.shape_keys.key_blocks[addon.mesh.output.SHAPE_KEY_NAME]
        assert np.abs(helpers.key_coords(key) - start).max() > 1e-3
    else:
        assert np.abs(helpers.coords(written) - start).max() > 1e-3
        helpers.mesh_io.write_vertex_coords(written.data, start)  # the stylized positions out of the way
        written.data.update()
    lost = differences(before, layers(written))
    assert not lost, "changed by %s output: %s" % (output, ", ".join(lost))
    if written is not obj:  # and the original is untouched, positions included
        assert np.array_equal(helpers.coords(obj), start) and not differences(before, layers(obj))


def _in_a_collection_with_a_transform(obj):
    props = bpy.data.collections.new("Props")
    bpy.context.scene.collection.children.link(props)
    props.objects.link(obj)
    bpy.context.scene.collection.objects.unlink(obj)
    obj.location, obj.rotation_euler, obj.scale = (1.0, 2.0, 3.0), (0.1, 0.2, 0.3), (1.5, 1.5, 0.5)
    obj.material_slots[1].link = 'OBJECT'  # an object-linked slot must come along too
    obj.material_slots[1].material = bpy.data.materials.new("Green")
    bpy.context.view_layer.update()
    return helpers.activate(obj)


@pytest.mark.parametrize("use_modifiers", [False, True])
def test_new_object_has_the_collection_transform_and_materials(addon, use_modifiers):
    obj = _in_a_collection_with_a_transform(decorated_suzanne("Monkey"))
    objects = len(bpy.data.objects)
    assert helpers.stylize(STEPS, output='NEW_OBJECT', use_modifiers=use_modifiers) == {'FINISHED'}
    new = bpy.context.active_object
    assert new.name == "Monkey_stylized" and new.data.name == "Monkey_stylized"
    assert len(bpy.data.objects) == objects + 1 and new.select_get() and not obj.select_get()
    assert [c.name for c in new.users_collection] == ["Props"]
    assert np.allclose(np.array(new.matrix_world), np.array(obj.matrix_world), atol=0)
    assert [s.material.name for s in new.material_slots] == ["Red", "Green"]
    assert [s.link for s in new.material_slots] == ['DATA', 'OBJECT']
    assert obj.display_type == new.display_type == 'TEXTURED'  # wireframe only during a run
    assert obj.data.users == 1  # not a linked duplicate: the original keeps its own mesh


def _subdivided_suzanne(levels=1):
    obj = helpers.suzanne(levels=0)
    obj.modifiers.new("Subdivision", 'SUBSURF').levels = levels
    return obj


def test_use_modifiers_with_new_object_stylizes_the_subdivided_mesh(addon):
    obj = _subdivided_suzanne()
    start = helpers.coords(obj)
    shown = helpers.evaluated_coords(obj)
    assert len(shown) > 3 * len(start)
    assert helpers.stylize(100, output='NEW_OBJECT', use_modifiers=True) == {'FINISHED'}
    new = bpy.context.active_object
    assert len(new.modifiers) == 0 and len(new.data.vertices) == len(shown)  # the modifier is applied
    assert np.array_equal(helpers.coords(obj), start) and len(obj.modifiers) == 1
    assert np.array_equal(helpers.evaluated_coords(obj), shown)
    # The stylized surface is the subdivided one (not a stylized cage smoothed afterwards).
    before = helpers.aligned_share(new, helpers.AXES, positions=shown)
    after = helpers.aligned_share(new, helpers.AXES)
    print("axis-aligned share of the subdivided Suzanne: %.3f -> %.3f" % (before, after))
    assert before < 0.15 and after > 0.5


@pytest.mark.parametrize("output", ['MESH', 'SHAPE_KEY'])
def test_a_topology_changing_stack_refuses_mesh_and_shape_key_output(addon, output):
    obj = _subdivided_suzanne()
    start, meshes = helpers.coords(obj), len(bpy.data.meshes)
    with pytest.raises(RuntimeError, match="New Object, or bake"):
        helpers.stylize(5, output=output, use_modifiers=True)
    assert np.array_equal(helpers.coords(obj), start) and obj.data.shape_keys is None
    assert len(bpy.data.meshes) == meshes  # the evaluated copy read for the check is gone
    assert helpers.stylize(5, output=output, use_modifiers=False) == {'FINISHED'}  # the base mesh still can


def _with_smile(obj, value):
    obj.shape_key_add(name="Basis", from_mix=False)
    smile = obj.shape_key_add(name="Smile", from_mix=False)
    moved = helpers.key_coords(smile)
    moved[:, 2] += np.float32(0.3) * moved[:, 0] ** 2
    smile.data.foreach_set("co", moved.reshape(-1))
    smile.value = value
    obj.data.update()
    return obj


def test_use_modifiers_reads_the_shape_as_shown(addon):
    # The same stylization as on a plain copy of the shape Blender shows (keys mixed in).
    obj = _with_smile(helpers.suzanne(levels=1), 0.8)
    shown = helpers.evaluated_coords(obj)
    plain = helpers.scene_kit.duplicate(obj, "Plain")
    plain.shape_key_clear()
    helpers.mesh_io.write_vertex_coords(plain.data, shown)
    helpers.activate(plain)
    helpers.stylize(STEPS)
    expected = helpers.coords(plain)
    helpers.activate(obj)
    assert helpers.stylize(STEPS, use_modifiers=True, output='NEW_OBJECT') == {'FINISHED'}
    assert np.array_equal(helpers.coords(bpy.context.active_object), expected)
    helpers.activate(obj)
    assert helpers.stylize(STEPS, use_modifiers=False, output='NEW_OBJECT') == {'FINISHED'}
    assert not np.array_equal(helpers.coords(bpy.context.active_object), expected)  # the base shape


def test_reset_after_mesh_output_with_use_modifiers_restores_the_base_mesh(addon):
    obj = _with_smile(helpers.suzanne(levels=1), 1.0)
    base = helpers.key_coords(obj.data.shape_keys.key_blocks["Basis"])
    helpers.stylize(STEPS, use_modifiers=True, output='MESH')
    assert not np.array_equal(helpers.key_coords(obj.data.shape_keys.key_blocks["Basis"]), base)
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert np.array_equal(helpers.key_coords(obj.data.shape_keys.key_blocks["Basis"]), base)


def test_reset_of_a_new_object_puts_its_start_shape_back(addon):
    obj = _subdivided_suzanne()
    shown = helpers.evaluated_coords(obj)
    helpers.stylize(STEPS, use_modifiers=True, output='NEW_OBJECT')
    new = bpy.context.active_object
    assert bpy.ops.object.gauss_stylize_reset() == {'FINISHED'}
    assert np.array_equal(helpers.coords(new), shown)


def _new_object_run(addon, obj):
    settings = obj.gauss_stylization
    settings.use_modifiers, settings.output = True, 'NEW_OBJECT'
    addon.run.session.ensure_style_slot(settings)
    return addon.run.session.Session(obj)


def test_a_cancelled_new_object_run_leaves_nothing_behind(addon):
    obj = _subdivided_suzanne()
    counts, start = (len(bpy.data.objects), len(bpy.data.meshes)), helpers.coords(obj)
    run = _new_object_run(addon, obj)
    run.step(3)
    new = bpy.data.objects["Suzanne_stylized"]
    assert obj.display_type == 'WIRE' and new.display_type == 'TEXTURED'  # the result is seen through it
    assert obj.select_get() and not new.select_get()  # the panel still shows the original's settings
    assert run.object_alive()
    run.cancel()
    assert (len(bpy.data.objects), len(bpy.data.meshes)) == counts
    assert obj.display_type == 'TEXTURED' and np.array_equal(helpers.coords(obj), start)


def test_the_new_object_deleted_mid_run_stops_it(addon):
    obj = _subdivided_suzanne()
    run = _new_object_run(addon, obj)
    run.step(2)
    bpy.data.objects.remove(bpy.data.objects["Suzanne_stylized"])
    assert not run.object_alive()
    run.cancel()  # removes the orphaned mesh, touches no freed data
    assert "Suzanne_stylized" not in bpy.data.meshes and obj.display_type == 'TEXTURED'


# -- several objects (targets.py, live_run.py) -------------------------------------------

def _subdivided_pair():
    """Two subdivided Suzannes, 'A' and 'B' ('B' active, both selected), Use Modifiers and New Object."""
    a, b = _subdivided_suzanne(), _subdivided_suzanne()
    a.name, b.name = "A", "B"
    b.location.x = 3.0
    for obj in (a, b):
        obj.gauss_stylization.use_modifiers, obj.gauss_stylization.output = True, 'NEW_OBJECT'
    helpers.activate(b)
    a.select_set(True)
    return a, b


def test_new_object_output_for_every_selected_object(addon):
    a, b = _subdivided_pair()
    starts = {obj.name: helpers.coords(obj) for obj in (a, b)}
    shown = helpers.evaluated_coords(a)
    assert bpy.ops.object.gauss_stylize(iterations=STEPS) == {'FINISHED'}
    for obj in (a, b):
        new = bpy.data.objects[obj.name + "_stylized"]
        assert len(new.modifiers) == 0 and len(new.data.vertices) == len(shown)
        assert np.abs(helpers.coords(new) - shown).max() > 1e-3
        assert np.array_equal(helpers.coords(obj), starts[obj.name]) and obj.display_type == 'TEXTURED'


def test_a_cancelled_live_run_of_several_new_objects_leaves_nothing(addon):
    a, b = _subdivided_pair()
    counts = (len(bpy.data.objects), len(bpy.data.meshes))
    live = helpers.live_run([b, a])
    live.tick(budget=1e9)
    assert {"A_stylized", "B_stylized"} <= set(bpy.data.objects.keys())
    assert a.display_type == b.display_type == 'WIRE'
    live.cancel()
    assert (len(bpy.data.objects), len(bpy.data.meshes)) == counts
    assert a.display_type == b.display_type == 'TEXTURED'


def test_a_live_run_cancelled_while_preparing_drops_the_evaluated_copies(addon):
    # Use Modifiers reads each object's evaluated mesh into a mesh datablock when the run is planned;
    # cancelled before any Session took them over, they must go too.
    a, b = _subdivided_pair()
    meshes = len(bpy.data.meshes)
    live = addon.run.live_run.LiveRun(addon.run.targets.plan_objects(helpers.Reports(), [b, a]))  # set-up running
    assert len(bpy.data.meshes) == meshes + 2
    live.cancel()
    assert len(bpy.data.meshes) == meshes
