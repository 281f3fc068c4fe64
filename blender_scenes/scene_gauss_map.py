"""A style from an example's whole Gauss map (From Gauss Map) beside From Object's 32 dominant
directions: the example is the bunny with a Decimate modifier; From Object keeps its largest facet
directions, the Gauss Map style every face direction with its share of the area, so the cow takes on
the example's whole spread of facets (docs/styles.md#gauss-map). The labels give the earth mover's
distance of each result's normal distribution from the example's (radians; scripts/measure_gauss_map.py)."""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests", "common"))
import render_kit  # noqa: E402
import scene_from_example  # noqa: E402
import scene_kit  # noqa: E402
from measures import fibonacci_lattice, mesh_gauss_histogram, sphere_emd  # noqa: E402

NAME = "gauss_map"
STEPS = 300
CELLS = 400  # the histograms' lattice, as scripts/measure_gauss_map.py's default
EXAMPLE_FACES = 440  # a low-poly bunny with more directions than From Object's 32 can hold


def _distance(obj, example):
    evaluated = example.evaluated_get(bpy.context.evaluated_depsgraph_get())
    mesh = evaluated.to_mesh()
    try:
        ex_co = scene_kit.addon.mesh_io.read_vertex_coords(mesh)
        ex_tris = scene_kit.addon.mesh_io.read_loop_triangles(mesh)[0]
    finally:
        evaluated.to_mesh_clear()
    tris = scene_kit.addon.mesh_io.read_loop_triangles(obj.data)[0]
    lattice = fibonacci_lattice(CELLS)
    return sphere_emd(mesh_gauss_histogram(scene_kit.coords(obj), tris, lattice),
                      mesh_gauss_histogram(ex_co, ex_tris, lattice), lattice)


def build():
    example = scene_from_example.low_poly_example(EXAMPLE_FACES)
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.color(source, render_kit.ORIGINAL_COLOR)
    faces = len(example.evaluated_get(bpy.context.evaluated_depsgraph_get()).data.polygons)
    objects = [example, source]
    labels = ["Low-poly example\n(%d faces)" % faces, "Original\nEMD %.3f" % _distance(source, example)]
    for name, operator in (("From Object", bpy.ops.object.gauss_style_from_object),
                           ("From Gauss Map", bpy.ops.object.gauss_style_from_gauss_map)):
        styled = render_kit.color(scene_kit.duplicate(source, name), render_kit.STYLIZED_COLOR)
        scene_kit.activate(styled)
        if operator(source=example.name) != {'FINISHED'}:
            raise RuntimeError("%s failed" % name)
        scene_kit.stylize(styled, None, iterations=STEPS)
        distance = _distance(styled, example)
        print("  %-15s EMD to the example %.4f" % (name, distance))
        objects.append(styled)
        labels.append("%s\nEMD %.3f" % (name, distance))
    render_kit.show_grid(objects, labels, columns=4, spacing_x=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
