"""Square Flat Regions: a large flat region (a cylinder's cap, a pot's lid) keeps a round outline under
the Cubic method and at low Lambda; with the setting the faces around it turn towards the axes of its
outline and the outline becomes a square (docs/styles.md#square-flat-regions). The meshes of the
setting's tests (tests/common/flat_meshes.py), Cubic Stylization at lambda 0.2 until converged, seen from
above; the label gives the cap's squareness (its upward faces' area over the smallest square holding
them: a circle's is 0.785)."""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests", "common"))
import flat_meshes  # noqa: E402
import render_kit  # noqa: E402
import scene_kit  # noqa: E402
from measures import squareness  # noqa: E402

NAME = "square_flat_regions"
FINISH = dict(camera_direction=(0.25, -1.0, 1.1))


def _object(name, make):
    V, F = make()
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(V.tolist(), [], F.tolist())
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    scene_kit.set_flat(obj)
    return obj


def build():
    objects, labels = [], []
    for shape, make in (("Cylinder", flat_meshes.capped_cylinder), ("Pot", flat_meshes.pot)):
        for on in (False, True):
            obj = render_kit.color(_object("%s %s" % (shape, "on" if on else "off"), make),
                                   render_kit.STYLIZED_COLOR)
            scene_kit.stylize(obj, [dict(preset='CUBE')], iterations=0, method='CUBIC', cubic_lambda=0.2,
                              square_flat_regions=on)
            tris = scene_kit.addon.mesh_io.read_loop_triangles(obj.data)[0]
            value = squareness(scene_kit.coords(obj), tris)
            print("  %-14s squareness %.3f" % (obj.name, value))
            objects.append(obj)
            labels.append("%s, %s\nsquareness %.2f" % (shape, "on" if on else "off", value))
    render_kit.show_grid(objects, labels, columns=4, spacing_x=3.0)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
