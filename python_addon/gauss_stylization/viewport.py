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


def viewport_region_at(context, x, y):
    """(area, region) of the 3D viewport drawing region under window pixel (x, y), or None
    over its sidebar, header or toolbar (they overlap the main region) and elsewhere."""
    for area in context.window.screen.areas:
        if area.type != 'VIEW_3D' or not _inside(area, x, y):
            continue
        # Sidebar and headers overlap the main region, so they are tested first.
        if any(region.type != 'WINDOW' and _inside(region, x, y) for region in area.regions):
            return None
        for region in area.regions:
            if region.type == 'WINDOW' and _inside(region, x, y):
                return area, region
    return None


def over_viewport(context, event):
    """Is the mouse over a 3D viewport's drawing region (not its sidebar, header or toolbar)?

    Clicks elsewhere must reach the UI, so settings can be changed while running.
    """
    return viewport_region_at(context, event.mouse_x, event.mouse_y) is not None
