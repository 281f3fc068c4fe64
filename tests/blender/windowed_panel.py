"""The sidebar panels in a real window: they are redrawn when an operator changes them, every
label fits the sidebar's default width, the Gauss sphere highlights the selected custom normal
and labels the axes, draw callbacks leave the gpu state as they found it, the live run's "settling"
row has its numbers as a tooltip, slot names and Custom normals are readable in their lists, a
bake's start leaves the sub-panels in place, a slot at Sigma 12 settles live and an object that kept the
paper's normal step shows it in the Solver panel (sidebar_old_step.png); and screenshots of the sidebar (idle, live run, a
Custom slot with 20 normals, the slot list, the Bake panel, the settling tooltip, the sidebar's
first drawings of a bake: bake_start_*.png). Run by
run_windowed.sh after the other parts, with windowed_kit.py's helpers as ``d``:

    blender --factory-startup --enable-event-simulate -P tests/blender/windowed_panel.py -- BUILD_DIR

Screenshots (cropped to the sidebar) go to BUILD_DIR/screenshots/sidebar_*.png
(scripts/panel_screenshots.sh copies them to docs/screenshots/); the summary to
BUILD_DIR/screenshots/windowed_panel_result.txt.
"""

import os
import sys
import tempfile
import time

import bpy
import gpu
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import windowed_kit as d  # noqa: E402  (also sets up the paths and the window options)
import rig  # noqa: E402
from panel_recorder import draw, labels, props  # noqa: E402
from windowed_actions import area_screenshot  # noqa: E402

from gauss_stylization import settings_io, ui  # noqa: E402  (windowed_kit put the add-on on sys.path)
from gauss_stylization.bake import bake_ui  # noqa: E402
from gauss_stylization.handles import handle_tool  # noqa: E402
from gauss_stylization.sphere import gauss_sphere, sphere_overlay  # noqa: E402
from gauss_stylization.view.sidebar import label_width, list_row_width, text_width  # noqa: E402

TIME_LIMIT = 480.0  # seconds (idle: about a minute; a busy 2-core machine redraws slowly)
SIDEBAR_SHOTS = ("sidebar_idle.png", "sidebar_live_run.png", "sidebar_custom_normals.png", "sidebar_bake.png")
drawn = {"sidebar": 0.0, "shown": None}


def panel_state(context):
    """What the Styles panel shows that the operators below change: the slots and the active one's rotation."""
    obj = context.active_object
    settings = obj.gauss_stylization if obj is not None and obj.type == 'MESH' else None
    if settings is None:
        return None
    return len(settings.styles), tuple(round(a, 5) for slot in settings.styles for a in slot.orientation)


class VIEW3D_PT_gauss_redraw_probe(bpy.types.Panel):
    """Tells the driver when the Gauss tab of the sidebar was last drawn and what the panels showed
    then (no header, nothing drawn)."""
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Gauss"
    bl_label = ""
    bl_options = {'HIDE_HEADER'}
    bl_order = -1000  # first in the tab, so it is drawn however long the panels below it grow

    def draw(self, context):
        drawn["sidebar"] = time.monotonic()
        drawn["shown"] = panel_state(context)


# -- gpu state around the add-on's draw callbacks ------------------------------------------

gpu_states = {}  # (stage, "before" / "after") -> set of (blend, depth test) seen
# What a draw callback before the add-on's leaves (another add-on's, say): not Blender's defaults,
# so that a callback setting those defaults at its end does not pass for one that restores.
STATE_BEFORE = ('ADDITIVE', 'LESS_EQUAL')


def _state_probe(stage, when):
    def probe():
        if when == "before":
            gpu.state.blend_set(STATE_BEFORE[0])
            gpu.state.depth_test_set(STATE_BEFORE[1])
        gpu_states.setdefault((stage, when), set()).add((gpu.state.blend_get(), gpu.state.depth_test_get()))
        if when == "after":  # Blender's own state again for what it draws next
            gpu.state.blend_set('NONE')
            gpu.state.depth_test_set('NONE')
    return probe


def bracket_the_draw_handlers():
    """Draw handlers run in the order added: a probe before and one after the add-on's own, per stage.
    The one before sets STATE_BEFORE, the one after records what it finds and puts back Blender's."""
    handlers = [handle_tool._handler, sphere_overlay._handler]
    for handler in handlers:
        handler.remove()
    probes = []
    for stage in ('POST_VIEW', 'POST_PIXEL'):
        probes.append(bpy.types.SpaceView3D.draw_handler_add(_state_probe(stage, "before"), (), 'WINDOW', stage))
    for handler in handlers:
        handler.add()
    for stage in ('POST_VIEW', 'POST_PIXEL'):
        probes.append(bpy.types.SpaceView3D.draw_handler_add(_state_probe(stage, "after"), (), 'WINDOW', stage))
    return probes


# -- screenshots ---------------------------------------------------------------------------

def sidebar():
    return d.view3d()[1]['UI']


def save_png(pixels, name):
    height, width = pixels.shape[:2]
    image = bpy.data.images.new(name, width, height, alpha=True)
    image.pixels.foreach_set(np.ascontiguousarray(pixels, np.float32).ravel())
    image.filepath_raw = os.path.join(d.SHOTS, name)
    image.file_format = 'PNG'
    image.save()
    bpy.data.images.remove(image)


def scroll_sidebar(clicks):
    """Turn the mouse wheel over the sidebar: ``clicks`` down (negative: up)."""
    region = sidebar()
    x, y = region.x + region.width // 2, region.y + region.height // 2
    d.window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
    for _ in range(abs(clicks)):
        d.window().event_simulate(type='WHEELDOWNMOUSE' if clicks > 0 else 'WHEELUPMOUSE', value='PRESS', x=x, y=y)


def sidebar_shot(name):
    """Generator: a screenshot of the sidebar alone, saved as BUILD/screenshots/``name``."""
    yield 0.4  # let the panels draw first
    area, _ = d.view3d()
    region = sidebar()
    pixels = area_screenshot(os.path.join(d.SHOTS, "area_" + name), keep=False)
    x, y = region.x - area.x, region.y - area.y
    save_png(pixels[y:y + region.height, x:x + region.width], name)
    path = os.path.join(d.SHOTS, name)
    d.check("sidebar screenshot %s saved" % name, os.path.exists(path) and os.path.getsize(path) > 5000)


# -- scenarios -----------------------------------------------------------------------------

def redrawn_after(name, operator, limit=1.0, settle=5.0):
    """Generator: run ``operator`` (a callable: it may only start the operator, e.g. open its
    dialog) with the pointer away from the sidebar, wait until what the panel shows has changed
    (at most ``settle`` seconds), then check ``name`` = the sidebar was drawn showing the change
    within ``limit`` seconds of it."""
    d.window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=d.viewport_point()[0], y=d.viewport_point()[1])
    yield 0.8  # whatever the move redraws is drawn by now
    before = panel_state(bpy.context)
    operator()
    deadline = time.monotonic() + settle
    while time.monotonic() < deadline and panel_state(bpy.context) == before:
        yield 0.02
    now = panel_state(bpy.context)
    changed = time.monotonic()
    while time.monotonic() < changed + limit and drawn["shown"] != now:
        yield 0.05
    d.check(name, now != before and drawn["shown"] == now,
            "panel state %s -> %s, the sidebar last drawn %s" % (before, now, drawn["shown"]))


def operator_redraws_the_sidebar(name):
    obj = d.activate(bpy.data.objects[name])
    with d.override():
        bpy.ops.mesh.primitive_ico_sphere_add(location=(4, 0, 0))
    example = bpy.context.active_object
    example.name = "Example"
    d.activate(obj)
    example.select_set(True)  # From Object offers the other selected mesh as the example
    yield 0.5
    x, y = d.viewport_point()

    def from_object():  # as from the panel: its dialog opens under the pointer, Enter confirms
        with d.override():
            bpy.ops.object.gauss_style_from_object('INVOKE_DEFAULT')
        d.window().event_simulate(type='RET', value='PRESS', x=x, y=y)
        d.window().event_simulate(type='RET', value='RELEASE', x=x, y=y)

    yield from redrawn_after("From Object (its dialog confirmed) redraws the sidebar at once", from_object)
    d.check("... and the new slot is there", len(obj.gauss_stylization.styles) == 1,
            "%d slots" % len(obj.gauss_stylization.styles))
    result = []

    def auto_orient():
        with d.override():
            result.append(bpy.ops.object.gauss_style_auto_orient('EXEC_DEFAULT'))

    yield from redrawn_after("Auto Orient redraws the sidebar at once", auto_orient)
    d.check("... after orienting the style", result == [{'FINISHED'}], str(result))
    bpy.data.objects.remove(example)
    obj.gauss_stylization.styles.clear()


def labels_fit_the_sidebar(name):
    """Every label of every Gauss panel, drawn for the sidebar as it is (default width, scale 1),
    fits its width: a long object name, several selected meshes, a live run, the bake panel."""
    obj = d.activate(bpy.data.objects[name])
    region = sidebar()
    scale = bpy.context.preferences.view.ui_scale  # (the system's adds the display's DPI: Xvfb's 75)
    d.check("the sidebar has Blender's default width at UI scale 1",
            scale == 1.0 and region.width < 300, "width %d, scale %s" % (region.width, scale))
    settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"preset": 'CUBE'}], "method": 'CUBIC'})
    original = d.coords(obj)
    yield from d.live_run(3)
    area, _ = d.view3d()
    too_wide = []
    with bpy.context.temp_override(window=d.window(), area=area, region=region):
        width = label_width()
        for panel in (ui.VIEW3D_PT_gauss_stylization, ui.VIEW3D_PT_gauss_styles, ui.VIEW3D_PT_gauss_solver,
                      bake_ui.VIEW3D_PT_gauss_bake):
            for text in labels(draw(panel)):
                if text_width(text) > width:
                    too_wide.append(text)
    d.check("every label fits the sidebar (%d px for text)" % width, not too_wide, str(too_wide))
    yield from d.end_with('ESC', "Esc after the label check restores the mesh", name, original)
    obj.gauss_stylization.method = 'GAUSS'


def _sphere_frame():
    area, regions = d.view3d()
    region = regions['WINDOW']
    where = sphere_overlay.placement(area, region)
    return gauss_sphere.Frame(where.x + region.x - area.x, where.y + region.y - area.y, where.radius)


def _seen(obj, direction):
    region = d.view3d()[1]['WINDOW']
    seen = sphere_overlay.view_rotation(region.data, obj) @ np.asarray(direction, float)
    return seen / np.linalg.norm(seen)


def _colour_near(pixels, x, y, test, reach=3):
    x, y = int(round(x)), int(round(y))
    patch = pixels[y - reach:y + reach + 1, x - reach:x + reach + 1, :3].reshape(-1, 3)
    return any(test(p) for p in patch)


def _orange(p):
    return p[0] > 0.85 and 0.35 < p[1] < 0.75 and p[2] < 0.35


def _white(p):
    return p.min() > 0.9


def sphere_highlights_and_axes(name):
    obj = d.activate(bpy.data.objects[name])
    rng = np.random.default_rng(7)
    normals = rng.normal(size=(20, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    settings_io.apply_dict(obj.gauss_stylization, {
        "styles": [{"preset": 'CUSTOM', "custom_normals": normals.tolist()}], "active_style_index": 0,
        "show_gauss_sphere": True})
    slot = obj.gauss_stylization.styles[0]
    facing = [i for i in range(20) if _seen(obj, normals[i])[2] > 0.3]
    active, other = facing[0], facing[-1]
    slot.active_normal_index = active
    yield 0.6
    pixels = area_screenshot(os.path.join(d.SHOTS, "sphere_highlight.png"), keep=False)
    where = _sphere_frame()

    def pixel_of(direction):
        return gauss_sphere.to_pixels(_seen(obj, direction)[None], where)[0]

    d.check("the Custom normal selected in the list is highlighted on the sphere",
            _colour_near(pixels, *pixel_of(normals[active]), _orange))
    d.check("... and the others are not", _colour_near(pixels, *pixel_of(normals[other]), _white)
            and not _colour_near(pixels, *pixel_of(normals[other]), _orange, reach=1))
    slot.active_normal_index = other
    yield 0.5
    pixels = area_screenshot(os.path.join(d.SHOTS, "sphere_highlight.png"), keep=False)
    reach = int(1.5 * where.radius)  # the sphere, its axis labels and its title, to look at
    save_png(pixels[max(0, int(where.y) - reach):int(where.y) + reach, max(0, int(where.x) - reach):int(where.x) + reach],
             "sphere_axes.png")
    d.check("selecting another row moves the highlight",
            _colour_near(pixels, *pixel_of(normals[other]), _orange)
            and not _colour_near(pixels, *pixel_of(normals[active]), _orange, reach=1))
    region = d.view3d()[1]['WINDOW']
    turn = sphere_overlay.view_rotation(region.data, obj)
    reddish = lambda p: p[0] > 0.6 and p[1] < 0.45 and p[2] < 0.45  # noqa: E731
    x_label = next((x, y) for axis, x, y, _ in gauss_sphere.axis_labels(turn, where) if axis == "X")
    d.check("the sphere's X axis is labelled (in red) where axis_labels puts it",
            _colour_near(pixels, *x_label, reddish, reach=6))
    scroll_sidebar(8)  # down to the list of normals
    yield from sidebar_shot(SIDEBAR_SHOTS[2])
    scroll_sidebar(-8)
    obj.gauss_stylization.show_gauss_sphere = False


def gpu_state_is_restored(name):
    """With the sphere shown and a live run with pins (both draw callbacks draw), what the
    handlers after the add-on's see is what those before it saw."""
    obj = d.activate(bpy.data.objects[name])
    gpu_states.clear()
    coords = d.coords(obj)
    top = np.flatnonzero(coords[:, 2] > np.percentile(coords[:, 2], 95))
    if "Top" in obj.vertex_groups:
        obj.vertex_groups.remove(obj.vertex_groups["Top"])
    obj.vertex_groups.new(name="Top").add([int(i) for i in top], 1.0, 'REPLACE')
    settings_io.apply_dict(obj.gauss_stylization, {"styles": [{"preset": 'CUBE'}], "pin_group": "Top",
                                                   "show_gauss_sphere": True})
    original = d.coords(obj)
    yield from d.live_run(3)
    yield 0.5
    op = d.live_operator()
    d.check("the live run with a Pin Group shows the pin hint", op is not None and any(
        "Drag a pin" in hint for hint in op.panel_state()[2]))
    yield from sidebar_shot(SIDEBAR_SHOTS[1])
    for stage in ('POST_VIEW', 'POST_PIXEL'):
        before, after = gpu_states.get((stage, "before"), set()), gpu_states.get((stage, "after"), set())
        d.check("the %s draw callbacks leave the blend and depth state as they found it" % stage,
                before == {STATE_BEFORE} and after == before, "before %s, after %s" % (sorted(before), sorted(after)))
    yield from d.end_with('ESC', "Esc after the gpu check restores the mesh", name, original)
    obj.gauss_stylization.pin_group = ""
    obj.gauss_stylization.show_gauss_sphere = False


def live_run_shows_convergence(name):
    obj = d.activate(bpy.data.objects[name])
    obj.gauss_stylization.pin_group = ""
    original = d.coords(obj)
    obj.gauss_stylization.tolerance = 1e-5  # it settles for long enough to hover over the row
    yield from d.live_run(5)
    op = d.live_operator()
    lines = [line[0] for line in op.panel_state()[1]] if op else []
    d.check("a live run says in words how far it has settled",
            any(text.startswith("settling, ") and text.endswith("%") for text in lines), str(lines))
    yield from settling_tooltip()
    yield from d.end_with('ESC', "Esc after the convergence check restores the mesh", name, original)
    obj.gauss_stylization.tolerance = 1e-3


def sharp_style_settles_and_the_old_step_shows(name):
    """A slot at Sigma 12 (above gauss_core.PAPER_STEP_MAX_SIGMA) settles in a live run; an object that
    kept the paper's step from an older file shows it in the Solver panel (sidebar_old_step.png)."""
    obj = d.activate(bpy.data.objects[name])
    settings = obj.gauss_stylization
    settings.pin_group = ""
    settings_io.apply_dict(settings, {"styles": [{"preset": 'CUBE', "sigma": 12.0}]})
    original = d.coords(obj)
    yield from d.live_run(400)
    op = d.live_operator()
    d.check("a live run at Sigma 12 settles", op is not None and op.session is not None and op.session.converged,
            "steps %s" % (op.session.steps if op and op.session else None))
    yield from d.end_with('ESC', "Esc after the Sigma 12 run restores the mesh", name, original)
    settings.paper_step_any_sigma = True  # what an object of settings version 4 loads with
    scroll_sidebar(15)  # the Solver panel is below the Styles panel
    yield from sidebar_shot("sidebar_old_step.png")
    scroll_sidebar(-15)
    shown = labels_and_props(ui.VIEW3D_PT_gauss_solver)
    d.check("the Solver panel shows the old step where it acts", "paper_step_any_sigma" in shown, str(shown))
    # Checkbox texts are cut with an ellipsis; this row's is no wider than Resolution Independent's above it,
    # which the screenshot shows whole.
    texts = [settings.bl_rna.properties[key].name for key in ("paper_step_any_sigma", "resolution_independent")]
    d.check("the old step's checkbox text is not cut", text_width(texts[0]) <= text_width(texts[1]), str(texts))
    settings.paper_step_any_sigma = False
    settings.styles.clear()


def labels_and_props(panel):
    area, _ = d.view3d()
    with bpy.context.temp_override(window=d.window(), area=area, region=sidebar()):
        return props(draw(panel))


def settling_tooltip():
    """Hover over the sidebar's "settling" row until Blender shows its tooltip (the numbers);
    the 3D view with it goes to BUILD/screenshots/settling_tooltip.png."""
    region = sidebar()
    area, _ = d.view3d()
    x = region.x + region.width // 2
    found = None
    for y in range(region.y + region.height - 20, region.y + region.height // 2, -8):
        d.window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x, y=y)
        yield 0.05
        bpy.context.window_manager.clipboard = ""
        try:
            with bpy.context.temp_override(window=d.window(), area=area, region=region):
                bpy.ops.ui.copy_python_command_button()
        except RuntimeError:
            continue
        if "gauss_run_details" in bpy.context.window_manager.clipboard:
            found = y
            break
    d.check("the settling row is a button with the numbers", found is not None and
            "Tolerance" in bpy.context.window_manager.clipboard, bpy.context.window_manager.clipboard)
    if found is None:
        return
    d.window().event_simulate(type='MOUSEMOVE', value='NOTHING', x=x + 1, y=found)
    yield 1.5  # Blender's tooltip delay
    area_screenshot(os.path.join(d.SHOTS, "settling_tooltip.png"))


# -- the sidebar as drawn, frame by frame ---------------------------------------------------

class SidebarFrames:
    """Every frame the sidebar draws, read back at the end of its drawing: [(seconds, (H, W, 4) pixels,
    frames the bake running then had baked)]."""

    def __init__(self):
        self.frames = []
        self.handler = bpy.types.SpaceView3D.draw_handler_add(self._grab, (), 'UI', 'POST_PIXEL')

    def _grab(self):
        region = bpy.context.region
        if region is None or region != sidebar():
            return
        buffer = gpu.state.active_framebuffer_get().read_color(0, 0, region.width, region.height, 4, 0, 'FLOAT')
        buffer.dimensions = region.width * region.height * 4
        job = getattr(d.live_operator(), "_job", None)  # a bake's
        self.frames.append((time.monotonic(), np.array(buffer, np.float32).reshape(region.height, region.width, 4),
                            job.done if job is not None else None))

    def stop(self):
        bpy.types.SpaceView3D.draw_handler_remove(self.handler, 'UI')



def _rows_that_differ(a, b, below):
    """Rows (counted from the top, from ``below`` down) where two frames differ visibly."""
    a, b = a[::-1][below:], b[::-1][below:]
    if a.shape != b.shape:
        return a.shape[0]
    return int(np.count_nonzero(np.abs(a[..., :3] - b[..., :3]).max(axis=(1, 2)) > 0.1))


def bake_start_keeps_the_panels_in_place(name):
    """For a second or two after a bake started, the sub-panels' headers were drawn over
    Stylize, Output and Pin Group: the bake's box pushes them down, Blender slides them there at its
    next redraws, and the bake's first frame came before those and held the screen as it was. Now what
    the sidebar shows while the first frame is baked (its last drawing before) has them in place, and
    they stay there while the frame count grows (past 10, where a longer count wrapped its line)."""
    obj = bpy.data.objects[name]
    obj.hide_set(True)
    with d.override():
        capsule = rig.bent_capsule(frames=(1, 40), segments=(48, 24))
    scroll_sidebar(-20)
    yield 1.0
    for old in os.listdir(d.SHOTS):
        if old.startswith("bake_start_"):
            os.remove(os.path.join(d.SHOTS, old))
    frames = SidebarFrames()
    folder = tempfile.mkdtemp(prefix="gauss_bake_")
    area, regions = d.view3d()
    with bpy.context.temp_override(window=d.window(), area=area, region=regions['UI']):  # as its button does
        bpy.ops.object.gauss_bake_animation('INVOKE_DEFAULT', frame_start=1, frame_end=40,
                                            filepath=os.path.join(folder, "capsule.pc2"))
    started = time.monotonic()
    deadline = started + 60.0
    while time.monotonic() < deadline and not any(done and done >= 12 for _at, _pixels, done in frames.frames):
        yield 0.1
    sidebar().tag_redraw()
    yield 0.5
    frames.stop()
    d.press('ESC', *d.viewport_point())
    yield 0.5
    before_first = [pixels for _at, pixels, done in frames.frames if done == 0]
    settled = frames.frames[-1][1] if frames.frames else None
    for index, (at, pixels, done) in enumerate(frames.frames[:8]):
        save_png(pixels, "bake_start_%02d_%.2fs_frame%s.png" % (index, at - started, done))
    if not before_first or settled is None:
        d.check("the sidebar was drawn before the bake's first frame and after", False, str(len(frames.frames)))
    else:
        top = int(0.3 * settled.shape[0])  # below the bake's box, whose frame count changes
        rows = _rows_that_differ(before_first[-1], settled, top)
        d.check("while a bake's first frame is baked the sidebar shows its panels in place",
                rows <= 4,  # a glitch moves hundreds
                "%d rows differ from the settled sidebar (%d drawings before it)" % (rows, len(before_first)))
        # The box kept its height as the count grew ("frame 9" to "frame 10" wrapped its line once, and
        # the panels below slid down while the bake held the screen): every later drawing is the same.
        moved = [(round(at - started, 2), done, _rows_that_differ(before_first[-1], pixels, top))
                 for at, pixels, done in frames.frames if done]
        d.check("while the bake goes on the panels below its box stay where they were",
                moved and all(rows <= 4 for _at, _done, rows in moved), str(moved))
    bpy.data.objects.remove(capsule)
    bpy.data.objects.remove(bpy.data.objects["Rig"])
    obj.hide_set(False)
    d.activate(obj)


def slot_names_and_normals_fit(name):
    """Slot names were cut to "Stre..." (half of the list's row) and the Custom normals ran
    their numbers together ("-0.79-0.19 0.58"). A screenshot of both, and their texts against the row."""
    obj = d.activate(bpy.data.objects[name])
    settings = obj.gauss_stylization
    if "Head" not in obj.vertex_groups:
        obj.vertex_groups.new(name="Head")
    settings_io.apply_dict(settings, {"styles": [
        {"preset": 'CUBE', "name": "Stretched Cube"}, {"preset": 'TRUNCATED_PYRAMID', "vertex_group": "Head"},
        {"preset": 'CUSTOM', "custom_normals": [[-0.79, -0.19, 0.58], [-0.99, -0.99, -0.99]] * 10}],
        "active_style_index": 2})
    scroll_sidebar(-20)
    yield from sidebar_shot("sidebar_slots.png")
    area, _ = d.view3d()
    with bpy.context.temp_override(window=d.window(), area=area, region=sidebar()):
        unit = 20.0 * bpy.context.preferences.system.ui_scale
        row = list_row_width()
        cut = [slot.name for slot in settings.styles
               if ui.slot_row(slot, row, text_width, unit)[1] is None
               and text_width(slot.name) > row - ui.ICON_UNITS * unit]
        widest = max(text_width(ui.normal_text(n.vector)) for n in settings.styles[2].custom_normals)
    d.check("every slot's name fits its row in the list at the default width", not cut, str(cut))
    room = (1.0 - ui.NORMAL_NUMBER_SHARE) * (row - 0.6 * unit) - 0.5 * unit  # 20 rows: a scroll bar
    d.check("a Custom normal's X Y Z fit their row, apart", widest <= room, "%.0f px for %.0f px" % (widest, room))
    settings.styles.clear()


def scenario():
    name = d.set_up()
    # The Solver and Bake panels are closed by default; for the screenshots they are registered open
    # before the sidebar first draws them (the panels themselves are the add-on's).
    for panel in (ui.VIEW3D_PT_gauss_solver, bake_ui.VIEW3D_PT_gauss_bake):
        bpy.utils.unregister_class(panel)
        panel.bl_options = set()
    for panel in (ui.VIEW3D_PT_gauss_solver, bake_ui.VIEW3D_PT_gauss_bake):  # in their order
        bpy.utils.register_class(panel)
    probes = bracket_the_draw_handlers()
    yield 1.0
    yield from d.open_gauss_tab()
    yield from sidebar_shot(SIDEBAR_SHOTS[0])
    bpy.utils.register_class(VIEW3D_PT_gauss_redraw_probe)
    yield from operator_redraws_the_sidebar(name)
    bpy.utils.unregister_class(VIEW3D_PT_gauss_redraw_probe)
    yield from labels_fit_the_sidebar(name)
    yield from live_run_shows_convergence(name)
    yield from sharp_style_settles_and_the_old_step_shows(name)
    yield from gpu_state_is_restored(name)
    yield from sphere_highlights_and_axes(name)
    yield from slot_names_and_normals_fit(name)
    yield from bake_start_keeps_the_panels_in_place(name)
    obj = d.activate(bpy.data.objects[name])
    obj.gauss_stylization.styles.clear()
    scroll_sidebar(15)  # the Bake panel is at the bottom
    yield from sidebar_shot(SIDEBAR_SHOTS[3])
    for probe in probes:
        bpy.types.SpaceView3D.draw_handler_remove(probe, 'WINDOW')


d.start(scenario(), "windowed_panel_result.txt", time_limit=TIME_LIMIT)
