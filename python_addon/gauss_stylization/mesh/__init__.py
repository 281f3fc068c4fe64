"""Meshes in and out: Blender mesh <-> numpy (mesh_io.py), what a run stylizes (source.py), where
its result goes (output.py, with the bake's Mesh Cache modifier: cache_modifier.py) and the shape
Reset restores (rest_store.py). Imports settings/ and the top-level errors.py, native.py.
"""
