"""Windowed scenarios of the interactive tools (issue 9): the Gauss sphere overlay and
editing on it. Run by windowed_driver.py, whose helpers (check, press, window, view3d,
live_run, wait_steps, ...) arrive as ``d``; every press and drag is simulated.
"""

import os

import bpy
import numpy as np

from gauss_stylization import gauss_sphere, native, settings_io, sphere_overlay, styles


# -- where things are on screen ---------------------------------------------------------

def _main_region(d):
    area, regions = d.view3d()
    return area, regions['WINDOW']


def sphere_frame(d):
    """The sphere's Frame in window pixels."""
    area, region = _main_region(d)
    where = sphere_overlay.placement(area, region)
    return gauss_sphere.Frame(where.x + region.x, where.y + region.y, where.radius)


def direction_pixel(d, obj, direction):
    """Window pixel where an object-space direction shows on the sphere (and whether it faces us)."""
    area, region = _main_region(d)
    seen = sphere_overlay.view_rotation(region.data, obj) @ np.asarray(direction, float)
    seen /= np.linalg.norm(seen)
    x, y = gauss_sphere.to_pixels(seen[None], sphere_frame(d))[0]
    return (x, y), seen[2] > 0


def shown_normals(obj):
    slot = styles.active_slot(obj.gauss_stylization)
    normals = np.array(slot.custom_normal_list(), float).reshape(-1, 3)
    return normals @ styles.rotation_matrix(slot).T


def pixels_of(d, obj):
    return [direction_pixel(d, obj, n)[0] for n in shown_normals(obj)]


def free_spot(d, obj):
    """A pixel on the sphere far from every dot of the active Custom slot."""
    where = sphere_frame(d)
    angles = np.radians(np.arange(0, 360, 30))
    spots = [(where.x + 0.5 * where.radius * np.cos(a), where.y + 0.5 * where.radius * np.sin(a)) for a in angles]
    dots = pixels_of(d, obj)
    return max(spots, key=lambda p: min(np.hypot(p[0] - x, p[1] - y) for x, y in dots))


def near(a, b, tolerance=1.5):
    return np.hypot(a[0] - b[0], a[1] - b[1]) <= tolerance


def drag(d, start, end, moves=6, button='LEFTMOUSE'):
    """Press at ``start``, move to ``end`` in ``moves`` steps, release there (window pixels)."""
    win = d.window()
    x0, y0 = (int(round(v)) for v in start)
    x1, y1 = (int(round(v)) for v in end)
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0, y=y0)
    win.event_simulate(type=button, value='PRESS', x=x0, y=y0)
    for k in range(1, moves + 1):
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x0 + (x1 - x0) * k // moves,
                           y=y0 + (y1 - y0) * k // moves)
    win.event_simulate(type=button, value='RELEASE', x=x1, y=y1)


def area_screenshot(d, path):
    """The 3D view as an (H, W, 4) float array (row 0 at the bottom), saved to ``path``."""
    area, _ = d.view3d()
    if os.path.exists(path):
        os.remove(path)
    with bpy.context.temp_override(window=d.window(), area=area):
        bpy.ops.screen.screenshot_area(filepath=path)
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)


def disc_mask(d, shape, grow=1.0):
    """Pixels of an area screenshot inside the sphere's outline (``grow`` times its radius)."""
    area, _ = d.view3d()
    where = sphere_frame(d)
    rows, cols = np.mgrid[0:shape[0], 0:shape[1]]
    return np.hypot(cols + area.x - where.x, rows + area.y - where.y) <= grow * where.radius


# -- scenarios ----------------------------------------------------------------------------

def sphere_is_drawn(d, name):
    """The overlay appears in the corner when switched on, and nowhere else."""
    obj = d.activate(bpy.data.objects[name])
    settings = obj.gauss_stylization
    settings_io.apply_dict(settings, {"styles": [{"preset": 'CUBE'}], "active_style_index": 0,
                                      "show_gauss_sphere": False})
    yield 0.5
    off = area_screenshot(d, os.path.join(d.SHOTS, "sphere_off.png"))
    settings.show_gauss_sphere = True
    yield 0.5
    on = area_screenshot(d, os.path.join(d.SHOTS, "sphere_overlay.png"))
    area, _ = d.view3d()
    d.check("screenshot of the Gauss sphere has the 3D view's size",
            on.shape[:2] == (area.height, area.width), "%s vs %dx%d" % (on.shape, area.height, area.width))
    changed = np.abs(on[..., :3] - off[..., :3]).sum(axis=2) > 0.05
    inside, around = disc_mask(d, on.shape), ~disc_mask(d, on.shape, grow=1.6)
    d.check("the Gauss sphere is drawn in its corner", changed[inside].mean() > 0.9,
            "%.2f of the disc changed" % changed[inside].mean())
    d.check("... and nothing else in the view changes", changed[around].mean() < 0.01,
            "%.4f changed elsewhere" % changed[around].mean())
    dots = [p for p, front in (direction_pixel(d, obj, n) for n in styles.make_style(
        native.core(), settings.styles[0]).normals) if front]
    white = [on[int(round(y)) - area.y, int(round(x)) - area.x, :3].min() > 0.9 for x, y in dots]
    d.check("the Cube style's preferred normals facing the viewer are white dots",
            dots and all(white), "%d of %d dots white" % (sum(white), len(dots)))


def _custom(obj, normals):
    settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"preset": 'CUSTOM', "custom_normals": normals}],
                                                   "active_style_index": 0, "show_gauss_sphere": True})


def sphere_editing(d, name):
    obj = d.activate(bpy.data.objects[name])
    _custom(obj, [(0.0, 0.0, 1.0)])
    d.push_undo("Custom style for sphere editing")
    yield 0.5
    where = sphere_frame(d)
    target = free_spot(d, obj)
    d.press('LEFTMOUSE', int(target[0]), int(target[1]))
    yield 0.4
    pixels = pixels_of(d, obj)
    d.check("a click on the Gauss sphere adds a normal where it was clicked",
            len(pixels) == 2 and near(pixels[1], (int(target[0]), int(target[1]))), str(pixels))

    start = pixels[-1]
    end = (start[0] + 25, start[1] + 20)
    drag(d, start, end)
    yield 0.4
    moved = pixels_of(d, obj)
    d.check("dragging a dot moves its normal under the mouse",
            len(moved) == 2 and near(moved[1], (int(end[0]), int(end[1]))) and near(moved[0], pixels[0]),
            str(moved))

    d.press('Z', *d.viewport_point(), ctrl=True)
    yield 0.5
    obj = bpy.data.objects[name]  # undo replaced the object's data
    undone = pixels_of(d, obj)
    d.check("Ctrl+Z undoes the drag (one step)", len(undone) == 2 and near(undone[1], pixels[1]), str(undone))

    first = pixels_of(d, obj)[0]
    d.press('RIGHTMOUSE', int(first[0]) + 3, int(first[1]) - 2)
    yield 0.4
    left = pixels_of(d, obj)
    d.check("a right-click on the sphere removes the nearest normal",
            len(left) == 1 and near(left[0], pixels[1]), str(left))
    d.press('RIGHTMOUSE', int(left[0][0]), int(left[0][1]))
    yield 0.4
    d.check("... but never the last one", len(pixels_of(d, obj)) == 1)

    empty = (where.x, where.y + 1.6 * where.radius)  # the grid above the sphere, left of the mesh
    d.press('LEFTMOUSE', int(empty[0]), int(empty[1]))
    yield 0.4
    d.check("a click beside the sphere keeps its meaning (deselects) and edits nothing",
            not obj.select_get() and len(pixels_of(d, obj)) == 1)
    d.activate(obj)
    settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"preset": 'CUBE'}]})
    d.press('LEFTMOUSE', int(where.x), int(where.y))
    yield 0.4
    d.check("with a preset style active a click on the sphere is an ordinary click (deselects)",
            not obj.select_get() and obj.gauss_stylization.styles[0].preset == 'CUBE')
    d.activate(obj)


def sphere_editing_during_a_run(d, name):
    obj = d.activate(bpy.data.objects[name])
    _custom(obj, [(0.0, 0.0, 1.0), (1.0, 0.0, 0.0)])
    original = d.coords(obj)
    yield from d.live_run(3)
    free = free_spot(d, obj)
    d.press('LEFTMOUSE', int(free[0]), int(free[1]))
    yield 0.3
    op = d.live_operator()
    d.check("a click on the sphere during a run adds a normal and leaves the run going",
            op is not None and len(obj.gauss_stylization.styles[0].custom_normals) == 3)
    steps = op.session.steps if op else 0
    yield from d.wait_steps(steps + 3)
    op = d.live_operator()
    d.check("... and the running solver takes it at its next steps",
            op is not None and len(op.session.applied["styles"][0]["custom_normals"]) == 3)
    yield from d.end_with('ESC', "Esc after editing on the sphere restores the mesh bit-exactly", name, original)
    obj.gauss_stylization.show_gauss_sphere = False


def scenario(d, name):
    yield from sphere_is_drawn(d, name)
    yield from sphere_editing(d, name)
    yield from sphere_editing_during_a_run(d, name)
