"""A small armature-animated mesh for the bake tests: a capsule bent by a two-bone rig."""

import math

import bpy
import numpy as np

import helpers

BEND_DEGREES = 60.0


def bent_capsule(frames=(1, 10), segments=(24, 16)):
    """A stretched UV sphere (z from -2 to 2) skinned to bones Lower and Upper; Upper bends about X
    from 0 at frames[0] to BEND_DEGREES at frames[1] (linear), so every frame has another shape."""
    obj = helpers.uv_sphere(*segments)
    obj.name = "Capsule"
    co = helpers.coords(obj)
    co[:, 2] *= 2.0
    helpers.mesh_io.write_vertex_coords(obj.data, co)
    obj.data.update()

    armature = bpy.data.armatures.new("Rig")
    rig = bpy.data.objects.new("Rig", armature)
    bpy.context.scene.collection.objects.link(rig)
    helpers.activate(rig)
    bpy.ops.object.mode_set(mode='EDIT')
    lower = armature.edit_bones.new("Lower")
    lower.head, lower.tail = (0, 0, -2), (0, 0, 0)
    upper = armature.edit_bones.new("Upper")
    upper.head, upper.tail = (0, 0, 0), (0, 0, 2)
    upper.parent = lower
    bpy.ops.object.mode_set(mode='OBJECT')

    # Weights blend over the middle third so the bend is smooth.
    upper_weight = np.clip((co[:, 2] + 0.67) / 1.33, 0.0, 1.0)
    for name, weights in (("Lower", 1.0 - upper_weight), ("Upper", upper_weight)):
        group = obj.vertex_groups.new(name=name)
        for index, weight in enumerate(weights):
            if weight > 0:
                group.add([index], float(weight), 'REPLACE')
    obj.modifiers.new("Armature", 'ARMATURE').object = rig

    bone = rig.pose.bones["Upper"]
    bone.rotation_mode = 'XYZ'
    for frame, degrees in zip(frames, (0.0, BEND_DEGREES)):
        bone.rotation_euler = (math.radians(degrees), 0.0, 0.0)
        bone.keyframe_insert("rotation_euler", frame=frame)
    for curve in rig.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = 'LINEAR'
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = frames
    scene.frame_set(frames[0])
    return helpers.activate(obj)


def shown_at(obj, frame):
    bpy.context.scene.frame_set(frame)
    return helpers.evaluated_coords(obj)
