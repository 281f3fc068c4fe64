"""The Gauss sphere: face normals as directions (directions.py), the sphere as drawn
(gauss_sphere.py), the overlay (sphere_overlay.py) and editing a Custom style on it
(sphere_editing.py), the surface the tools see (surface.py), and styles from data
(orientation.py, style_from_data.py). Imports run/ and the layers below it.
"""
