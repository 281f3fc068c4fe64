"""Screen areas a live run draws into and takes clicks from."""

import bpy


def existing_area(pointer):
    """The screen area at address ``pointer`` if it still exists, else None.

    Areas are not IDs: when one is freed (areas joined or closed, a file loaded)
    Python is not told, and a kept reference would write into freed memory. So
    the area is looked for among the live ones each time (a few dozen at most).
    """
    if pointer is None:
        return None
    for screen in bpy.data.screens:
        for area in screen.areas:
            if area.as_pointer() == pointer:
                return area
    return None


def redraw_viewports(context):
    for area in context.window.screen.areas if context.window else ():
        if area.type == 'VIEW_3D':
            area.tag_redraw()


def _inside(rect, x, y):
    return rect.x <= x < rect.x + rect.width and rect.y <= y < rect.y + rect.height


def over_viewport(context, event):
    """Is the mouse over a 3D viewport's drawing region (not its sidebar, header or toolbar)?

    Clicks elsewhere must reach the UI, so settings can be changed while running.
    """
    x, y = event.mouse_x, event.mouse_y
    for area in context.window.screen.areas:
        if area.type != 'VIEW_3D' or not _inside(area, x, y):
            continue
        # Sidebar and headers overlap the main region, so they are tested first.
        return not any(region.type != 'WINDOW' and _inside(region, x, y) for region in area.regions)
    return False
