"""What several windowed drivers do or read the same way, as a person would: a Move made with G, a
value typed into a sidebar field (found by asking Blender which property is under the mouse), a drag, a
key over the viewport, the navigation gizmo's buttons; and the 3D view's pixels from a screenshot.
Built on windowed_kit's window helpers."""

import os

import bpy
import numpy as np

from windowed_kit import check, press, view3d, viewport_point, window


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


def _property_under_mouse(x, y):
    """Generator: the mouse to (x, y); found["path"] = the data path of the property there (or "")."""
    area, regions = view3d()
    window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.02
    bpy.context.window_manager.clipboard = ""
    try:
        with bpy.context.temp_override(window=window(), area=area, region=regions['UI']):
            bpy.ops.ui.copy_data_path_button(full_path=False)
    except RuntimeError:  # no property under the mouse
        pass
    found["path"] = bpy.context.window_manager.clipboard


def find_sidebar_field(data_path):
    """Generator: hover down the sidebar and ask Blender which property is under the mouse;
    leaves the middle of ``data_path``'s row in found["at"] (None if not found). A place found
    before is checked first (the panel's layout rarely changes). A row below the sidebar's bottom is
    scrolled to, as an artist scrolls: the sidebar is scrolled down a few wheel clicks at a time."""
    yield from _find_sidebar_field_here(data_path)
    ui = view3d()[1]['UI']
    middle = (ui.x + ui.width // 2, ui.y + ui.height // 2)
    # Not in view: from the top of the sidebar, then a few wheel clicks further down at a time.
    for wheel, clicks in [('WHEELUPMOUSE', 40)] + [('WHEELDOWNMOUSE', SCROLL_CLICKS)] * SCROLL_TRIES:
        if found["at"] is not None:
            return
        window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=middle[0], y=middle[1])
        for _ in range(clicks):
            window().event_simulate(type=wheel, value='PRESS', x=middle[0], y=middle[1])
        yield 0.4
        found.pop(data_path, None)
        yield from _find_sidebar_field_here(data_path)


SCROLL_TRIES, SCROLL_CLICKS = 6, 4


def _find_sidebar_field_here(data_path):
    """find_sidebar_field without scrolling."""
    known = found.get(data_path)
    if known is not None:
        yield from _property_under_mouse(*known)
        if found["path"] == data_path:
            found["at"] = known
            return
    ui = view3d()[1]['UI']
    x = ui.x + ui.width // 2 + 20  # the value column of a property row
    row = int(18 * bpy.context.preferences.system.ui_scale)  # a little less than a row's height
    hit = None
    for y in range(ui.y + ui.height - row // 2, ui.y, -row):  # every row is hit once
        yield from _property_under_mouse(x, y)
        if found["path"] == data_path:
            hit = y
            break
    if hit is not None:  # the row's middle: the median of the points around the hit that are on it
        on_row = [hit]
        for y in range(hit - row, hit + row + 1, 3):
            yield from _property_under_mouse(x, y)
            if found["path"] == data_path:
                on_row.append(y)
        hit = sorted(on_row)[len(on_row) // 2]
    found["at"] = found[data_path] = (x, hit) if hit is not None else None


found = {}


def type_into_field(data_path, text):
    """Generator: click the sidebar field of ``data_path``, type ``text`` and press Enter."""
    yield from find_sidebar_field(data_path)
    check("the sidebar shows the field %s" % data_path, found["at"] is not None)
    if found["at"] is None:
        return
    win = window()
    x, y = found["at"]
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.1
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y)
    yield 0.1
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x, y=y)  # a click starts editing the number as text
    yield 0.2
    win.event_simulate(type='A', value='PRESS', ctrl=True)  # select what is there
    win.event_simulate(type='A', value='RELEASE', ctrl=True)
    for char in text:
        key = {"0": 'ZERO', "1": 'ONE', "2": 'TWO', "3": 'THREE', "4": 'FOUR', "5": 'FIVE', "6": 'SIX',
               "7": 'SEVEN', "8": 'EIGHT', "9": 'NINE', ".": 'PERIOD'}[char]
        win.event_simulate(type=key, value='PRESS', unicode=char)
        win.event_simulate(type=key, value='RELEASE')
    win.event_simulate(type='RET', value='PRESS')
    win.event_simulate(type='RET', value='RELEASE')
    yield 0.3


def drag(x, y, dx, dy, steps=10, **modifiers):
    """Generator: press the left button at (x, y), move by (dx, dy) in ``steps``, release."""
    win = window()
    win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    yield 0.05
    win.event_simulate(type='LEFTMOUSE', value='PRESS', x=x, y=y, **modifiers)
    for i in range(1, steps + 1):
        yield 0.03
        win.event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + dx * i // steps, y=y + dy * i // steps)
    yield 0.05
    win.event_simulate(type='LEFTMOUSE', value='RELEASE', x=x + dx, y=y + dy, **modifiers)
    yield 0.3


def key(event_type, **modifiers):
    """Generator: a key pressed over the viewport, then time for Blender to act on it."""
    press(event_type, *viewport_point(), **modifiers)
    yield 0.5


def navigation_gizmo_buttons():
    """Centres of the rotation gizmo and the zoom button as Blender 3.4 lays them out
    (view3d_gizmo_navigate.c): top right of the region's part no header or sidebar covers."""
    area, regions = view3d()
    preferences = bpy.context.preferences
    scale = preferences.system.ui_scale
    right = regions['UI'].x if area.spaces.active.show_region_ui else regions['WINDOW'].x + regions['WINDOW'].width
    top = regions['TOOL_HEADER'].y if area.spaces.active.show_region_tool_header else regions['HEADER'].y
    offset = (preferences.view.gizmo_size_navigate_v3d / 2 + 10) * scale
    rotate = (int(right - offset), int(top - offset))
    zoom = (int(right - 30 * scale * 0.75), int(top - offset * 2.1))
    return rotate, zoom


def find_sidebar_button(idname):
    """Generator: hover down the sidebar asking Blender which operator's button is under the mouse;
    found["button"] = the middle of ``idname``'s button (None if not found)."""
    area, regions = view3d()
    region = regions['UI']
    x = region.x + region.width // 2
    found["button"] = None
    for y in range(region.y + region.height - 10, region.y, -9):
        window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        yield 0.02
        bpy.context.window_manager.clipboard = ""
        try:
            with bpy.context.temp_override(window=window(), area=area, region=region):
                bpy.ops.ui.copy_python_command_button()
        except RuntimeError:
            continue
        if idname in bpy.context.window_manager.clipboard:
            found["button"] = (x, y)
            return
