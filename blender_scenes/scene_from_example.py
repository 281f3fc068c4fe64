"""A style from a low-poly example (From Object): the example's dominant face directions
(area-weighted clusters of its face normals, at most 32) become a Custom style, so the
stylized cow takes on the example's facets. The example is the bunny with a Decimate
modifier (From Object reads what the viewport shows, modifiers included)."""

import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_kit  # noqa: E402
import scene_kit  # noqa: E402

NAME = "from_example"
LAMBDA, SIGMA, STEPS = 20.0, 8.0, 300
EXAMPLE_FACES = 60       # the Decimate modifier's target
EXAMPLE_COLOR = (0.40, 0.62, 0.45, 1.0)


def low_poly_example(faces=EXAMPLE_FACES):
    """The bunny with a Decimate modifier down to about ``faces`` faces."""
    example, _ = scene_kit.demo_mesh(scene_kit.BUNNY, "Example")
    decimate = example.modifiers.new("Decimate", 'DECIMATE')
    decimate.ratio = min(1.0, faces / len(example.data.polygons))
    render_kit.color(example, EXAMPLE_COLOR)
    return example


def build():
    example = low_poly_example()
    source, _ = scene_kit.demo_mesh(scene_kit.SPOT, "Original")
    render_kit.color(source, render_kit.ORIGINAL_COLOR)
    styled = render_kit.color(scene_kit.duplicate(source, "From example"), render_kit.STYLIZED_COLOR)
    scene_kit.activate(styled)
    result = bpy.ops.object.gauss_style_from_object(source=example.name)  # the default Max Directions
    if result != {'FINISHED'}:
        raise RuntimeError("gauss_style_from_object returned %s" % result)
    slot = styled.gauss_stylization.styles[0]
    slot.sigma = SIGMA
    found = len(slot.custom_normals)
    print("  %d directions taken from the example" % found)
    scene_kit.stylize(styled, None, lam=LAMBDA, iterations=STEPS)
    faces = len(example.evaluated_get(bpy.context.evaluated_depsgraph_get()).data.polygons)
    render_kit.show_grid([example, source, styled],
                         ["Low-poly example\n(%d faces)" % faces, "Original",
                          "Style from the example\n(%d directions, sigma %g)" % (found, SIGMA)], columns=3, spacing_x=2.7)


if __name__ == "__main__":
    render_kit.run(sys.modules[__name__])
