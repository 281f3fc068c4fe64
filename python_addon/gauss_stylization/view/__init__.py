"""Blender's screen: which clicks land in the free viewport and what to redraw (viewport.py),
drawing with the gpu module in every supported Blender (gpu_compat.py), and the sidebar's panel kit
(sidebar.py). Imports settings/ and the top-level errors.py, native.py.
"""
