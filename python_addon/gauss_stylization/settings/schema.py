"""Every setting of the add-on, each written once.

The PropertyGroups (properties.py), the JSON round-trip and the settings writer
(settings_io.py), the validation before a run (validation.py), what a live run
does when a setting changes (run/session.py) and the panel rows (view/sidebar.py)
are all derived from these tables. Defaults and hard ranges of what the solver owns
(lam, sigma, mu, axis_contribution, admm_iterations, cubic_lambda, tolerance; the default of
keep_volume), the preset registry and the methods come from the solver (native.facts()), never from here.
A field whose default changed says since which settings version and what it was before, which
versioning.py writes out for objects of older files.

A new setting is one line in its table (kinds: fields.py), plus its use in the
solver call for slot fields (styles.make_style); see python_addon/README.md.
"""

from .. import native
from .fields import (
    Bool, Choice, Direction, Euler, FilePath, Float, GaussMap, Index, Int, Live, Normals, Panel, Slots, Text,
    VertexGroup,
)

FACTS = native.facts()
CUSTOM = 'CUSTOM'
REGION_THRESHOLD = 0.5  # styles.face_styles (one style per face): a face is in a region above this mean weight
PIN_THRESHOLD = 0.5     # a vertex is pinned when its pin-group weight is above this
# A scripted run of 0 steps runs until converged; it stops after this many steps if it has not by then
# (a mesh that keeps changing, a Tolerance below what the shape reaches), so a script always ends.
UNTIL_CONVERGED_CAP = 5000
NEW_OBJECT_SUFFIX = "_stylized"  # New Object output: '<name>_stylized'
# The ID property of a New Object copy holding its run's recipe (mesh/follow_store.py): the copy
# Follow Edits and Replay re-make from its source.
FOLLOW_RECIPE_KEY = "_gauss_follow"
# Style Reach's colour scale ends here: a face this many degrees or more from its preferred normal is red.
REACH_SCALE_DEGREES = 30.0
CUSTOM_NUMBER = 99  # enum number of Custom in saved files; presets are numbered 0, 1, ... in PRESETS order
GAUSS_MAP = 'GAUSS_MAP'
GAUSS_MAP_NUMBER = 98  # enum number of Gauss Map (an example's whole normal distribution) in saved files


def preset_identifier(name):
    """Solver preset name -> enum identifier ('square_pyramid' -> 'SQUARE_PYRAMID')."""
    return name.upper()


def preset_label(name):
    return name.replace("_", " ").title()


# The Lambda at which a preset of the solver's PRESET_LAMBDA (one that needs a lambda of its own) shows
# its look in the add-on, where new objects are Resolution Independent; the solver's figure is where its
# measures are taken, which on Spot is past the look (rendered: docs/styles.md#sheet-metal).
LOOK_LAMBDA = {"sheet_metal": 20.0}


def look_lambda(identifier):
    """The Lambda the slot's style needs to show (LOOK_LAMBDA), or None for a style that shows at any."""
    return LOOK_LAMBDA.get(identifier.lower()) if identifier != CUSTOM else None


def _follows(settings):
    """Follow Edits is shown where it acts: New Object output, or on a copy such a run kept."""
    return settings.output == 'NEW_OBJECT' or FOLLOW_RECIPE_KEY in settings.id_data.keys()


def _follow_edits_changed(settings, _context):
    # The follower lives in run/follow.py, above this module: it registers itself here.
    for listener in FOLLOW_EDITS_LISTENERS:
        listener(settings.id_data)


FOLLOW_EDITS_LISTENERS = []  # callables(obj) told when an object's Follow Edits is switched


def _preset_sigma(identifier):
    """The sigma a new slot of this style starts at: the preset's own where it has one (Sheet Metal)."""
    own = native.preset_strengths().get(identifier.lower())
    return own[0] if own and identifier != CUSTOM else FACTS.defaults["sigma"]


def _preset_items():
    # .blend files store the number, so preset i of the solver's registry is number i
    # (the registry only ever appends; see docs/architecture.md).
    strengths = native.preset_strengths()

    def tip(name):
        if name in strengths:  # no fixed directions: each face's own, unbent (docs/styles.md)
            return ("Each face turns towards one bending direction of its neighbourhood, like rolled or "
                    "folded sheet; it takes Sigma %g" % strengths[name][0]
                    + ("" if name not in LOOK_LAMBDA else " and shows from Lambda about %g" % LOOK_LAMBDA[name]))
        return "Prefer the face normals of a %s" % preset_label(name).lower()
    items = [(preset_identifier(name), preset_label(name), tip(name), number)
             for number, name in enumerate(FACTS.presets)]
    return items + [(CUSTOM, "Custom", "Prefer the normals listed below", CUSTOM_NUMBER),
                    (GAUSS_MAP, "Gauss Map", "Prefer an example object's whole normal distribution: each face turns "
                     "towards the example's nearest face direction (set by From Gauss Map)", GAUSS_MAP_NUMBER)]


DEFAULT_PRESET = preset_identifier(FACTS.defaults["preset"])
DEFAULT_PRESET_LABEL = preset_label(FACTS.defaults["preset"])

_METHOD_TIPS = {
    "gauss": "Gauss Stylization (Kohlbrenner et al. 2021): faces turn towards each slot's Style",
    "cubic": "Cubic Stylization (Liu & Jacobson 2019): surfaces turn towards the axes of a cube; a slot's "
             "Mu scales Cubic Lambda in its region and its Rotation turns the cube, its Style is not used",
}
CUBIC = preset_identifier("cubic")


def _method_items():
    # Saved files store the number: method i of the solver's list is number i (append only).
    return [(preset_identifier(name), name.title(), _METHOD_TIPS.get(name, ""), number)
            for number, name in enumerate(FACTS.methods)]


def is_cubic(settings):
    return settings.method == CUBIC


def _not_cubic(settings):
    return settings.method != CUBIC


def _old_rule_shown(name):
    """Where a Bool keeping an old rule of Resolution Independent for the Gauss method is shown: where it
    is on and acts, so that the artist sees it and can untick it."""
    return lambda settings: settings.resolution_independent and getattr(settings, name) and not is_cubic(settings)


def _paper_step_acts(settings):
    """Does paper_step_any_sigma change a run of these settings (an object's, or a dump of them, whose
    slots are dicts)? With the Gauss method, where a preset slot takes the solver's trust-region step
    (native.preset_takes_trust_region_step), and where a Custom slot may (sharper than the solver's
    limit; whether its normals stand apart is the solver's to say). Without the module: wherever a slot
    may."""
    if is_cubic(settings):
        return False
    limit = native.paper_step_max_sigma()

    def value(slot, name):
        return slot[name] if isinstance(slot, dict) else getattr(slot, name)

    def acts(slot):
        sigma, preset = value(slot, "sigma"), value(slot, "preset")
        if limit is None or preset == CUSTOM:
            return limit is None or sigma > limit
        if preset == GAUSS_MAP:
            return False
        return native.preset_takes_trust_region_step(preset.lower(), sigma)
    return any(acts(slot) for slot in settings.styles)


def _is_custom(slot):
    return slot.preset == CUSTOM


def _not_custom(slot):
    return slot.preset not in (CUSTOM, GAUSS_MAP)


def _is_gauss_map(slot):
    return slot.preset == GAUSS_MAP


MAX_FRAME = 1048574  # Blender's MAXFRAME: frames range over +-this


def _warm_start(settings):
    return settings.bake_warm_start


def _own_bake_range(settings):
    return not settings.bake_scene_range


def _has_rings(slot):
    """Does the slot's preset have rings (Cylinder, Cone, ...: whatever the solver says)?"""
    rings = native.ring_presets()
    return slot.preset not in (CUSTOM, GAUSS_MAP) and (rings is None or slot.preset.lower() in rings)


# GaussNormal: one preferred normal of a Custom style.
NORMAL = (
    Direction("vector", "Normal", "Preferred face normal (object space, need not be unit length)",
              default=(0.0, 0.0, 1.0)),
)

# GaussMapCell: one direction of an example's Gauss map and its share of the example's area.
GAUSS_MAP_CELL = (
    Direction("vector", "Direction", "A face direction of the example (object space, unit length)",
              default=(0.0, 0.0, 1.0)),
    Float("share", "Share", "The example's share of area facing this direction", default=0.0, hard=(0.0, 1.0)),
)

def style_label(identifier):
    """What the panel calls a slot's Style ('OCTAHEDRON' -> "Octahedron", 'CUSTOM' -> "Custom")."""
    return next((item[1] for item in _preset_items() if item[0] == identifier), identifier)


def _follow_style(slot, _context):
    """A slot is called after its style until the artist renames it: a name that is a style's
    label (or empty) follows the Style. So does a Sigma left at a style's own (Sheet Metal's is
    sharper than the others'): it becomes the new style's."""
    if slot.name == "" or slot.name in {item[1] for item in _preset_items()}:
        slot.name = style_label(slot.preset)
    own = {_preset_sigma(item[0]) for item in _preset_items()}
    if slot.sigma in own:
        slot.sigma = _preset_sigma(slot.preset)


# GaussStyleSlot: one style and the region it applies to.
SLOT = (
    Choice("preset", "Style", "Shape whose face normals this region prefers, or your own normals",
           _preset_items(), DEFAULT_PRESET, live=Live.STYLES, panel=Panel.SLOT, update=_follow_style),
    # 'name' is what the UIList shows and renames (double-click). After 'preset', so that a saved
    # name is written after the Style (whose change renames a slot still called after its style).
    Text("name", "Name", default=DEFAULT_PRESET_LABEL),
    Float("sigma", "Sigma", "Sharpness: higher values pull normals closer to the preferred ones",
          soft=(0.1, 20.0), live=Live.STYLES, panel=Panel.SLOT),
    Float("mu", "Mu", "Strength of this style relative to the others",
          soft=(0.0, 10.0), live=Live.STYLES, panel=Panel.SLOT),
    Euler("orientation", "Orientation", "Rotation of the preferred normals (object space)",
          live=Live.STYLES, panel=Panel.SLOT, text="Rotation"),
    # Checked for every preset (a value saved with a cube must be usable once it is a cone),
    # shown only where it acts.
    Float("axis_contribution", "Axis Contribution", "Weight of the axis normals for presets that have them",
          live=Live.STYLES, panel=Panel.SLOT, text="Axis Weight", relevant=_not_custom, shown=_has_rings),
    VertexGroup("vertex_group", "Vertex Group", "Region of this style: its weights scale the style's strength "
                "(a face whose corners mostly carry a weight takes their mean; 0 leaves it to the other styles; where Regions "
                "overlap, their weighted strengths add up). Paint them in Weight Paint mode: a live run picks "
                "up the strokes when you return to Object Mode. Empty means the whole mesh, less what the "
                "other styles' Regions take",
                live=Live.REGIONS, panel=Panel.SLOT, text="Region"),
    Normals("custom_normals", "Custom Normals", "GaussNormal", live=Live.STYLES, panel=Panel.SLOT,
            relevant=_is_custom),
    Index("active_normal_index", "Active Normal"),
    # After custom_normals: a slot written from a dict gets its example before it is checked.
    GaussMap("gauss_map", "Gauss Map", "GaussMapCell", live=Live.STYLES, panel=Panel.SLOT, relevant=_is_gauss_map),
)

# GaussSettings: Object.gauss_stylization.
OBJECT = (
    Choice("method", "Method", "How the mesh is stylized", _method_items(),
           preset_identifier(FACTS.defaults["method"]), live=Live.SETTER, panel=Panel.METHOD),
    Float("cubic_lambda", "Cubic Lambda", "How cubic the shape becomes versus keeping its shape (0.2: the "
          "Cubic Stylization paper's default)", soft=(0.0, 2.0), live=Live.SETTER, panel=Panel.METHOD,
          text="Lambda", relevant=is_cubic),
    Float("lam", "Lambda", "How strongly faces follow their style versus keeping their shape",
          soft=(0.0, 20.0), live=Live.SETTER, panel=Panel.SOLVER, relevant=_not_cubic),
    Int("admm_iterations", "ADMM Iterations", "Inner iterations per solver step",
        live=Live.SETTER, panel=Panel.SOLVER, text="ADMM Iters", relevant=_not_cubic),
    Float("tolerance", "Tolerance", "A run has converged, and stops, when a step moves the mesh by less than "
          "this fraction of how far it has moved from its original shape", soft=(1e-4, 0.1), live=Live.SETTER,
          panel=Panel.SOLVER),
    Int("iterations", "Script Steps", "Steps run by Stylize when called from a script or in background mode; "
        "0: until converged (Tolerance), at most %d steps" % UNTIL_CONVERGED_CAP,
        default=100, hard=(0, 100000), panel=Panel.SOLVER),
    Int("proxy_threshold", "Proxy Threshold", "A live run on a mesh with more vertices than this stylizes a "
        "simplified copy of it (a proxy) that the whole mesh follows at every tick, and Enter finishes the whole "
        "mesh at full resolution (docs/interactive.md, Sculpt-sized meshes)", default=300000,
        hard=(100, 2 ** 31 - 1), soft=(10000, 2000000), panel=Panel.SOLVER, added=2),
    Bool("keep_volume", "Keep Volume", "After each step scale every closed part of the mesh about its centre "
         "back to its original volume (open parts: to their original area; parts with pinned vertices are "
         "left alone), so the shape does not shrink", live=Live.SETTER, panel=Panel.SOLVER),
    Bool("avoid_self_intersections", "Avoid Self-Intersections", "Never let the surface pass through itself: "
         "where a step would make faces cross or touch that did not at the start, their vertices are held "
         "back (for 3D printing and carving; each step takes longer: docs/performance.md, The guard's cost)",
         live=Live.SETTER, panel=Panel.SOLVER),
    Bool("resolution_independent", "Resolution Independent", "Lambda means the same at any mesh density, so a "
         "coarse and a fine mesh of the same shape are stylized alike (docs/resolution.md). Off: the paper's "
         "method, where a finer mesh is stylized more strongly", new_objects=True, since=2, live=Live.SETTER,
         panel=Panel.SOLVER),
    # Resolution Independent's rule before settings version 3, which objects saved under it with the setting
    # on keep (settings/versioning.py). Only the Gauss method's normal step reads it.
    Bool("weigh_finer_faces", "Weigh Finer Faces (Old)", "Resolution Independent as it was before "
         "2026-12-06, which this object was saved with: it also weighs the style of faces finer than the "
         "reference density by their area. Untick for today's rule, with which more runs settle "
         "(docs/resolution.md)", since=3, before=True, before_where=lambda s: s.resolution_independent,
         live=Live.SETTER, panel=Panel.SOLVER, shown=_old_rule_shown("weigh_finer_faces")),
    # The normal step before settings version 5, which objects saved under it with a sharp style keep.
    Bool("paper_step_any_sigma", "Paper's Step (Old)", "The normal step as it was before "
         "2026-12-07, which this object was saved with: the paper's one Newton step at every Sigma. Above Sigma "
         "8 it makes faces jump between preferred normals and a run never settles. Untick for today's step, "
         "which settles there for styles whose directions stand apart (docs/high_sigma.md)", since=5, before=True, before_where=_paper_step_acts,
         live=Live.SETTER, panel=Panel.SOLVER,
         shown=lambda s: s.paper_step_any_sigma and _paper_step_acts(s)),
    Bool("square_flat_regions", "Square Flat Regions", "Give large flat regions (a cap, a lid, a table top) "
         "straight, square outlines instead of round ones: the faces around each turn towards the axes of its "
         "outline, with either method (docs/styles.md, Square Flat Regions)", live=Live.SETTER,
         panel=Panel.SOLVER, added=2),
    Bool("use_modifiers", "Use Modifiers", "Stylize the mesh as it is shown: modifiers, armature and shape "
         "keys at the current frame (otherwise the base mesh, under the modifiers)", default=False,
         panel=Panel.MAIN),
    Choice("output", "Output", "Where the stylized coordinates go",
           (('MESH', "Mesh", "Move the vertices of the mesh itself", 0),
            ('SHAPE_KEY', "Shape Key",
             "Write the result into the shape key 'Gauss Stylized' to blend it with its slider", 1),
            ('NEW_OBJECT', "New Object", "Put the result into a new object '<name>%s' (same collection, "
             "transform and materials); the original stays as it is" % NEW_OBJECT_SUFFIX, 2)),
           'MESH', panel=Panel.MAIN),
    Bool("follow_edits", "Follow Edits", "New Object output: the kept copy is made again from its source whenever "
         "the source changes (Edit Mode, sculpting, modifiers, shape keys, the frame), off Blender's main thread; "
         "a quick preview shows first while the edits go on (docs/interactive.md, Follow Edits)", default=False,
         panel=Panel.MAIN, shown=_follows, update=_follow_edits_changed, added=2),
    VertexGroup("pin_group", "Pin Group", "Vertices in this group (weight above %g) keep their position"
                % PIN_THRESHOLD, live=Live.PINS, panel=Panel.MAIN),
    Choice("uncovered", "Uncovered Faces", "Where what the styles' Regions leave of a face goes when every "
           "style has a Region (a style without one takes it otherwise)",
           (('FIRST_SLOT', "First Style", "To the first style, whose own Region then is whole again: painting "
             "it changes nothing (the rule of files saved before Unstyled became the default)", 0),
            ('UNSTYLED', "Unstyled", "Nowhere: faces outside every Region only keep their shape, and a "
             "Region's weight below 1 stylizes less", 1)),
           'UNSTYLED', live=Live.REGIONS, panel=Panel.STYLES, text="Other Faces", since=1, before='FIRST_SLOT'),
    # The paint curve with Resolution Independent before settings version 4, which objects saved under it with
    # the setting on keep (settings/paint_curve.py, settings/versioning.py). Shown only where it is on.
    Bool("old_paint_curve", "Paint Curve (Old)", "How painted Region weights became strength with Resolution "
         "Independent up to settings version 3 (2026-12-06), which this object was saved with: weights below 1 "
         "stylized less than their share. Untick for today's curve, with which a painted weight acts about in "
         "proportion (docs/interactive.md, The paint curve)", default=False, since=4, before=True,
         before_where=lambda s: s.resolution_independent, live=Live.CURVE, panel=Panel.STYLES,
         shown=_old_rule_shown("old_paint_curve")),
    Int("bake_steps", "Bake Steps", "Solver steps per frame of an animation bake (with Warm Start the "
        "first frame runs Script Steps, the others continue from the previous frame)",
        default=10, hard=(1, 100000), soft=(1, 200), panel=Panel.BAKE),
    Bool("bake_warm_start", "Warm Start", "Bake Animation starts each frame from the previous frame's result "
         "(steady style, no flicker). Off: every frame is stylized on its own, so frame ranges baked apart "
         "(render farm) give the same frames", default=True, panel=Panel.BAKE),
    Int("bake_warmup_frames", "Warm-up", "With Warm Start, frames a farm chunk (bake/farm_cli.py) bakes "
        "before its first frame without writing them, so that frame continues a run as in one bake; more: "
        "closer to one bake, slower chunks", default=8, hard=(0, 100000), soft=(0, 50), panel=Panel.BAKE,
        shown=_warm_start, added=1),
    Bool("bake_scene_range", "Scene Range", "Bake Animation bakes the scene's frame range (Frame Start to End); "
         "off: the Start and End below", default=True, panel=Panel.BAKE),
    Int("bake_frame_start", "Start", "First frame Bake Animation bakes", default=1,
        hard=(-MAX_FRAME, MAX_FRAME), panel=Panel.BAKE, shown=_own_bake_range),
    Int("bake_frame_end", "End", "Last frame Bake Animation bakes", default=250,
        hard=(-MAX_FRAME, MAX_FRAME), panel=Panel.BAKE, shown=_own_bake_range),
    FilePath("bake_filepath", "Cache File", "The .pc2 file a bake writes (a path starting with // is relative "
             "to the .blend file); empty: '<object>_gauss.pc2' next to the .blend file, or in the temporary "
             "folder while the .blend file is not saved", panel=Panel.BAKE),
    Bool("show_gauss_sphere", "Show Gauss Sphere",
         "Draw the Gauss sphere in a corner of the 3D view: the active style's g as a heat map, its "
         "preferred normals as dots and the mesh's face normals as points. With a Custom style active, "
         "click the sphere to add a normal, drag a dot to move it, right-click to remove the nearest",
         default=False, panel=Panel.SPHERE, text="Gauss Sphere"),
    Bool("show_style_reach", "Show Style Reach",
         "Colour every face by its angle to the normal its style prefers (Sheet Metal: how far the normals "
         "around it spread from one great circle), green: reached, red: %g degrees or more, grey: no style; "
         "live during a run, in Object Mode, with the scale in the corner of the 3D view" % REACH_SCALE_DEGREES,
         default=False, panel=Panel.SPHERE, text="Style Reach", added=2),
    Slots("styles", "Styles", "GaussStyleSlot", SLOT, owner_name=lambda slot: "Style '%s'" % slot.name),
    Index("active_style_index", "Active Style"),
)


def field(table, name):
    return next(f for f in table if f.name == name)


def rows(table, panel):
    """The fields of ``table`` drawn in ``panel``, in order."""
    return [f for f in table if f.panel is panel]


SOLVER_SETTERS = tuple(f for f in OBJECT if f.live is Live.SETTER)  # Solver keyword = property = setter
