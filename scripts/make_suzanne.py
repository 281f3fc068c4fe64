"""Writes Blender's Suzanne, Catmull-Clark subdivided, as a triangle OBJ (for measurements outside Blender).

usage: blender -b --factory-startup --python-exit-code 1 -P scripts/make_suzanne.py -- OUT.obj [LEVELS]

LEVELS (default 2) is the Subdivision Surface level applied, as the add-on's default scene and tests
subdivide her; the faces written are the mesh's loop triangles, the triangles the solver sees. The
output is measuring material (docs/limitations.md): write it to a temporary or out/ folder, never
into the repository.
"""
import sys

import bmesh
import bpy


def suzanne_triangles(levels):
    bm = bmesh.new()
    bmesh.ops.create_monkey(bm)
    mesh = bpy.data.meshes.new("Suzanne")
    bm.to_mesh(mesh)
    bm.free()
    obj = bpy.data.objects.new("Suzanne", mesh)
    bpy.context.scene.collection.objects.link(obj)
    if levels:
        modifier = obj.modifiers.new("Subdivision", 'SUBSURF')
        modifier.levels = levels
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    result = bpy.data.meshes.new_from_object(evaluated)
    result.calc_loop_triangles()
    V = [tuple(v.co) for v in result.vertices]
    F = [tuple(t.vertices) for t in result.loop_triangles]
    return V, F


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not args:
        raise SystemExit(__doc__)
    levels = int(args[1]) if len(args) > 1 else 2
    V, F = suzanne_triangles(levels)
    with open(args[0], "w") as out:
        out.write("".join("v %.9g %.9g %.9g\n" % v for v in V))
        out.write("".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F))
    print("%s: %d vertices, %d faces" % (args[0], len(V), len(F)))


main()
