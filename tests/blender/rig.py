"""A small armature-animated mesh for the bake tests: a capsule bent by a two-bone rig."""

import bpy
import numpy as np

import helpers

BEND_DEGREES = 60.0


def bent_capsule(frames=(1, 10), segments=(24, 16)):
    """A stretched UV sphere (z from -2 to 2) whose upper half bends about X from 0 at frames[0] to
    BEND_DEGREES at frames[1] (linear; scene_kit.bending_rig), so every frame has another shape."""
    obj = helpers.uv_sphere(*segments)
    obj.name = "Capsule"
    co = helpers.coords(obj)
    co[:, 2] *= 2.0
    helpers.mesh_io.write_vertex_coords(obj.data, co)
    obj.data.update()

    # Weights blend over the middle third so the bend is smooth.
    upper_weight = np.clip((co[:, 2] + 0.67) / 1.33, 0.0, 1.0)
    helpers.scene_kit.bending_rig(obj, (0, 0, 0), (0, 0, 2), upper_weight, BEND_DEGREES, frames)
    return helpers.activate(obj)


def shown_at(obj, frame):
    bpy.context.scene.frame_set(frame)
    return helpers.evaluated_coords(obj)
