"""Pin targets as text: the redo panel and scripts (the operator's pin_targets property).

A kept live run stores where its drags left the pins (targets_json); the redo panel and a script's
Stylize move the pins there again before stepping (apply_targets_json). Only sessions and their
solvers are read, so a scripted run needs neither a viewport nor the handles (handles/handles.py).
"""

import json

import numpy as np

from ..errors import SettingsError


def targets_json(sessions):
    """'{"object name": [[x, y, z], ...]}': the pin targets of the sessions whose pins were moved
    away from where they started, in the order of the Pin Group's vertices; "" if none was."""
    moved = {}
    for session in sessions:
        targets = session.mesh_pin_targets()  # the mesh's, also where a proxy's pins moved them
        start = session.arrays.coords[np.asarray(session.fine_pins, np.int64)]
        if len(targets) and not np.array_equal(targets, start):
            moved[session.obj.name] = targets.tolist()
    return json.dumps(moved) if moved else ""


def apply_targets_json(sessions, text):
    """Move the pins of the named objects' sessions to the targets in ``text`` (targets_json's form).

    Raises SettingsError, naming the object, for unreadable text, an object that is not being
    stylized, a count that is not its Pin Group's or targets the solver refuses."""
    try:
        wanted = json.loads(text)
        if not isinstance(wanted, dict):
            raise ValueError("expected an object of object names")
    except ValueError as exc:
        raise SettingsError("Unreadable pin targets (%s)" % exc) from exc
    by_name = {session.obj.name: session for session in sessions}
    for name, targets in wanted.items():
        session = by_name.get(name)
        if session is None:
            raise SettingsError("Pin targets for '%s', which is not being stylized" % name)
        try:
            targets = np.asarray(targets, np.float64).reshape(-1, 3)
            if len(targets) != len(session.solver.pinned):
                raise ValueError("%d targets for %d pinned vertices" % (len(targets), len(session.solver.pinned)))
            session.move_pins(targets)
        except (ValueError, TypeError) as exc:
            raise SettingsError("Pin targets of '%s': %s" % (name, exc)) from exc
