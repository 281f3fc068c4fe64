"""Which objects Stylize acts on, and a plan for each of them.

Stylize acts on the active object and every other selected mesh object, each
with its own settings and solver. One that cannot be stylized (no faces, a
missing vertex group, already in a live run, sharing its mesh with another
target) is skipped with a message naming it while the others run; only when
none is left does Stylize fail.
"""

from ..errors import NativeModuleError, SettingsError
from ..settings.validation import object_problem
from . import runs
from .session import Plan, ensure_style_slot

TITLE = "Gauss Stylize"  # what the status bar, progress lines and messages call a run


def stylize_objects(context):
    """The active object if it is a mesh, then the other selected mesh objects by name."""
    active = context.active_object
    first = [active] if active is not None and active.type == 'MESH' else []
    others = sorted((obj for obj in context.selected_objects if obj.type == 'MESH' and obj != active),
                    key=lambda obj: obj.name)
    return first + others


def stylize_problem(context):
    """Why Stylize cannot run in ``context`` (None if it can)."""
    active = context.active_object
    if active is not None and active.type != 'MESH' and stylize_objects(context):
        problem = object_problem(context, need_mesh=False)  # the selected meshes are stylized
    else:
        problem = object_problem(context)
    if problem is not None:
        return problem
    if runs.is_running(active):
        return "Stylization is already running on this object"
    if runs.live_runs():
        # One live run at a time: a second one would keep undo off when the first is kept,
        # so that run's undo step would be lost. One run takes every selected mesh anyway.
        return "Stylize is already running on other objects; keep (Enter) or cancel (Esc) it first"
    return None


class Planned:
    """plans: one session.Plan per object to stylize, in stylize_objects() order.
    slot_added: the objects given a default style slot because they had none."""

    def __init__(self, plans, slot_added):
        self.plans, self.slot_added = plans, slot_added

    @property
    def objects(self):
        return [plan.obj for plan in self.plans]

    def give_up(self, plan):
        """``plan``'s object will not be stylized: take back the default slot it was given
        (a start that fails changes nothing, settings included), and drop the evaluated mesh copy
        it read for Use Modifiers."""
        plan.release()
        obj = plan.obj
        if obj in self.slot_added:
            self.slot_added.remove(obj)
            try:
                obj.gauss_stylization.styles.remove(0)
            except ReferenceError:  # deleted meanwhile
                pass

    def undo_added_slots(self):
        """Give up every plan: default slots taken back, evaluated copies dropped (a run cancelled
        while it was preparing changes nothing)."""
        for plan in self.plans:
            self.give_up(plan)


def report_skipped(operator, skipped, any_left):
    """Report the objects skipped ([(name, why)]): warnings while others go on, else one error
    (for a single object its message alone, as a script sees it)."""
    if any_left:
        for name, why in skipped:
            operator.report({'WARNING'}, "Skipped '%s': %s" % (name, why))
    elif len(skipped) == 1:
        operator.report({'ERROR'}, skipped[0][1])
    elif skipped:
        operator.report({'ERROR'}, "Nothing stylized: " + "; ".join("'%s': %s" % item for item in skipped))


def plan_objects(operator, objects):
    """Plan every object; report the skipped ones. Returns a Planned, or None (reported) if none is left."""
    plans, slot_added, skipped, by_mesh = [], [], [], {}
    for obj in objects:
        if runs.is_running(obj):
            skipped.append((obj.name, "it is already being stylized"))
            continue
        if obj.data.as_pointer() in by_mesh:
            skipped.append((obj.name, "it shares its mesh with '%s', which is stylized" % by_mesh[obj.data.as_pointer()]))
            continue
        added = ensure_style_slot(obj.gauss_stylization)
        try:
            plan = Plan(obj)
        except (SettingsError, NativeModuleError) as exc:
            if added:  # a failed start changes nothing a result depends on, settings included
                obj.gauss_stylization.styles.remove(0)
            skipped.append((obj.name, str(exc)))
            continue
        by_mesh[obj.data.as_pointer()] = obj.name
        plans.append(plan)
        if added:
            slot_added.append(obj)
    report_skipped(operator, skipped, any_left=bool(plans))
    if not plans:
        return None
    if slot_added:
        operator.report({'INFO'}, "No style slot yet: added a %s style to %s"
                        % (slot_added[0].gauss_stylization.styles[0].name,
                           ", ".join("'%s'" % obj.name for obj in slot_added)))
    return Planned(plans, slot_added)
