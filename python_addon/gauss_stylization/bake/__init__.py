"""Bakes to a point cache: the .pc2 format (pc2.py, no Blender needed), the bakes (bake.py), their
operators (bake_operators.py) and the Bake sub-panel (bake_ui.py). Imports run/ and the layers below it.
"""
