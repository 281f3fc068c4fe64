"""Screen areas a live run draws into, and which clicks are its own.

A click belongs to the run only in the *free* viewport: a 3D view's drawing
region, minus what Blender draws over it (headers, tool header, toolbar,
sidebar, the redo panel) and minus the navigation gizmo in its top-right
corner. Everything else, and every drag, belongs to Blender. Coordinates are
window pixels, as in event.mouse_x / mouse_y.
"""

import bpy

# The navigation gizmo's layout in unscaled pixels (Blender's view3d_gizmo_navigate): the
# rotation gizmo (diameter: Preferences > Viewport > Navigation Gizmo Size) sits this far from
# the visible region's corner, the buttons below it are 28 px with a 2 px margin. The margin is
# taken a bit wider than 3.4's 10 px so the rectangle also covers later versions' layout.
GIZMO_MARGIN = 20.0
GIZMO_BUTTON = 30.0
GIZMO_BUTTONS = 4        # zoom, pan, camera, perspective/orthographic (fewer when the view is locked)
UI_UNIT = 20.0           # Blender's UI_UNIT_X at scale 1


def redraw_viewports(context, sidebars=True):
    """Redraw the 3D views; ``sidebars``: their sidebars too (a run's ticks leave them out:
    redrawing every panel at every tick costs more than the tick itself on a slow machine)."""
    for area in context.window.screen.areas if context.window else ():
        if area.type != 'VIEW_3D':
            continue
        if sidebars:
            area.tag_redraw()
            continue
        for region in area.regions:
            if region.type == 'WINDOW':
                region.tag_redraw()


def redraw_sidebars(context):
    """Redraw the sidebar of every 3D view in every window: an operator that changes what the
    Gauss panels show must say so, or they stay as they were until the pointer passes over them."""
    for window in context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == 'VIEW_3D':
                for region in area.regions:
                    if region.type == 'UI':
                        region.tag_redraw()


class Rect:
    def __init__(self, xmin, ymin, xmax, ymax):
        self.xmin, self.ymin, self.xmax, self.ymax = xmin, ymin, xmax, ymax

    @classmethod
    def of(cls, item):
        """The rectangle of an area or region."""
        return cls(item.x, item.y, item.x + item.width, item.y + item.height)

    def contains(self, x, y):
        return self.xmin <= x < self.xmax and self.ymin <= y < self.ymax

    def overlaps(self, other):
        return (self.xmin < other.xmax and other.xmin < self.xmax
                and self.ymin < other.ymax and other.ymin < self.ymax)


def _shown(region):
    return region.width > 1 and region.height > 1  # hidden regions keep a 1-pixel size


def visible_rect(area, region):
    """The part of a 3D view's drawing ``region`` no header, toolbar or sidebar covers
    (they overlap it when Preferences > Interface > Region Overlap is on)."""
    rect = Rect.of(region)
    for other in area.regions:
        if other.type == 'WINDOW' or not _shown(other) or not Rect.of(other).overlaps(rect):
            continue
        if other.alignment == 'TOP':
            rect.ymax = min(rect.ymax, other.y)
        elif other.alignment == 'BOTTOM':
            rect.ymin = max(rect.ymin, other.y + other.height)
        elif other.alignment == 'LEFT':
            rect.xmin = max(rect.xmin, other.x + other.width)
        elif other.alignment == 'RIGHT':
            rect.xmax = min(rect.xmax, other.x)
    return rect


def navigation_gizmo_rect(area, region, preferences):
    """The rectangle of ``region`` taken by the navigation gizmo, or None when it is not shown."""
    space = area.spaces.active
    view = preferences.view
    show_rotate = view.mini_axis_type == 'GIZMO'
    show_buttons = view.show_navigate_ui
    if not (space.show_gizmo and space.show_gizmo_navigate and (show_rotate or show_buttons)):
        return None
    scale = preferences.system.ui_scale
    visible = visible_rect(area, region)
    corner_offset = (view.gizmo_size_navigate_v3d / 2.0 + GIZMO_MARGIN) * scale  # to the rotation gizmo's centre
    button = GIZMO_BUTTON * scale
    if view.mini_axis_type == 'GIZMO':
        first_button = corner_offset * 2.1
    elif view.mini_axis_type == 'MINIMAL':
        first_button = UI_UNIT * scale * 2.5 + view.mini_axis_size * preferences.system.pixel_size * 2.0
    else:
        first_button = button * 0.75
    left = visible.xmax - (2.0 * corner_offset if show_rotate else 1.5 * button)
    bottom = visible.ymax - (2.0 * corner_offset if show_rotate else 0.0)
    if show_buttons:
        bottom = min(bottom, visible.ymax - first_button - (GIZMO_BUTTONS - 0.5) * button)
    return Rect(left, bottom, visible.xmax, visible.ymax)


def viewport_region_at(context, x, y):
    """(area, region) of the 3D view drawing region under window point (x, y), or None over
    a header, the toolbar, the sidebar or the redo panel (they overlap it) and elsewhere."""
    if context.window is None:
        return None
    for area in context.window.screen.areas:
        if area.type != 'VIEW_3D' or not Rect.of(area).contains(x, y):
            continue
        if any(region.type != 'WINDOW' and _shown(region) and Rect.of(region).contains(x, y)
               for region in area.regions):
            return None
        for region in area.regions:
            if region.type == 'WINDOW' and Rect.of(region).contains(x, y):
                return area, region
        return None
    return None


def free_viewport_at(context, x, y):
    """Is window point (x, y) in the free part of a 3D view (see the module's docstring)?"""
    found = viewport_region_at(context, x, y)
    if found is None:
        return False
    gizmo = navigation_gizmo_rect(*found, context.preferences)
    return gizmo is None or not gizmo.contains(x, y)


def drag_distance_exceeded(context, start, end):
    """Has the mouse moved from ``start`` to ``end`` far enough for Blender to call it a drag?"""
    threshold = context.preferences.inputs.drag_threshold_mouse * context.preferences.system.ui_scale
    return max(abs(end[0] - start[0]), abs(end[1] - start[1])) > threshold
