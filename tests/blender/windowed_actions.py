"""What several windowed drivers do or read the same way: a Move made with G as a person makes it, and
the 3D view's pixels from a screenshot. Built on windowed_driver's window helpers."""

import os

import bpy
import numpy as np

from windowed_driver import press, view3d, viewport_point, window


def move_with_g(dx=60):
    """Generator: G over the viewport, the mouse moved, a click to confirm (one Move undo step; during
    a live run the click confirms the move and its release must not keep the run)."""
    x, y = viewport_point()
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.1
    win.event_simulate(type='G', value='PRESS', x=x, y=y)
    win.event_simulate(type='G', value='RELEASE', x=x, y=y)
    yield 0.2
    for i in range(1, 6):
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + dx * i // 5, y=y)
        yield 0.05
    press('LEFTMOUSE', x + dx, y)
    yield 0.3


def area_screenshot(path, keep=True):
    """The 3D view as an (H, W, 4) float array (row 0 at the bottom), from a screenshot saved to
    ``path`` (removed again unless ``keep``)."""
    area, _ = view3d()
    if os.path.exists(path):
        os.remove(path)
    with bpy.context.temp_override(window=window(), area=area):
        bpy.ops.screen.screenshot_area(filepath=path)
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    if not keep:
        os.remove(path)
    return pixels.reshape(height, width, 4)
