"""A Stylize run that goes through at once: scripts, background mode, the redo panel.

The solvers of all objects are set up first (on a worker thread, progress
shown meanwhile), then each object runs its steps. Steps go in chunks of about
CHUNK_SECONDS, and at most a tenth of the run, so progress can be shown between
them; chunking does not change the result (n steps are n steps). With 0 steps
an object runs until converged (its last step changed it by less than its
Tolerance), at most schema.UNTIL_CONVERGED_CAP steps. An object that
cannot be set up or fails while stepping is restored and skipped with a message
naming it; the others are kept. The operator's one undo step covers them all.
Pin targets (pin_targets.targets_json's text) move the named objects' pins before
the first step; targets that cannot be used stop the whole run, nothing changed.
"""

import math
import time

from ..errors import SettingsError
from ..settings import schema
from .pin_targets import apply_targets_json
from .progress import ProgressReport
from .session import Session
from .solver_setup import SolverSetup
from .targets import TITLE, report_skipped

CHUNK_SECONDS = 0.1


def _set_up(planned, report):
    """Sessions for the plans whose solvers could be built, and [(name, why)] of the others."""
    results = SolverSetup(planned.plans).wait(report)
    sessions, failed = [], []
    for plan, result in zip(planned.plans, results):
        try:
            if isinstance(result, Exception) or result is None:
                raise result or SettingsError("the set-up did not finish")
            sessions.append(Session(plan, result))
        except SettingsError as exc:
            failed.append((plan.name, str(exc)))
            planned.give_up(plan)
    return sessions, failed


def _closeness(reldv, tolerance):
    """How far a run until converged is, 0..1: reldV falls from about 1 after the first step to the
    tolerance, roughly geometrically, so the share of that fall on a log scale."""
    if not math.isfinite(reldv) or reldv >= 1.0:
        return 0.0
    return min(math.log(reldv) / math.log(tolerance), 1.0)


def _advance(session, count, show):
    """Run ``count`` steps of ``session`` in chunks, or with ``count`` 0 run until converged, at most
    schema.UNTIL_CONVERGED_CAP steps. show(fraction of this object, text): its progress.
    Returns the steps taken."""
    until = count == 0
    limit = schema.UNTIL_CONVERGED_CAP if until else count
    tolerance = session.solver.tolerance
    chunk, done, fraction = 1, 0, 0.0
    most = max(1, limit // 10)  # a chunk never skips a tenth of the whole run
    while done < limit:
        steps = min(chunk, limit - done)
        start = time.perf_counter()
        if until:
            taken = session.step_until(steps)
        else:
            session.step(steps)
            taken = steps
        done += taken
        seconds = max((time.perf_counter() - start) / max(taken, 1), 1e-6)
        chunk = max(1, min(most, int(CHUNK_SECONDS / seconds)))
        if not until:
            show(done / limit, "Stylizing '%s': step %d of %d" % (session.name, done, count))
            continue
        if session.at_rest:
            show(1.0, "Stylizing '%s': %s at step %d"
                 % (session.name, "held back" if session.held_back else "converged", done))
            break
        fraction = max(fraction, done / limit, _closeness(session.reldv, tolerance))
        show(fraction, "Stylizing '%s': step %d, until converged (reldV %.1e, Tolerance %g)"
             % (session.name, done, session.reldv, tolerance))
    return done


def _until_converged_note(session, steps):
    """(level, text) of how a run until converged ended."""
    if session.converged:
        return 'INFO', "'%s' converged after %d steps" % (session.name, steps)
    if session.held_back:
        return 'WARNING', ("'%s' stopped after %d steps, held back by Avoid Self-Intersections at %d "
                           "vertices short of where the style pulls them (it did not converge); the "
                           "shape is kept" % (session.name, steps, session.solver.held_vertices))
    unstable = (" and is unstable at these settings (lower Lambda or ADMM Iterations)"
                if session.unstable else "")
    return 'WARNING', ("'%s' did not converge within %d steps (its last step changed it by %.1e of its "
                       "displacement, its Tolerance is %g)%s; the shape after %d steps is kept"
                       % (session.name, steps, session.reldv, session.solver.tolerance, unstable, steps))


def run(operator, context, planned, steps, pin_targets=""):
    """Run every planned object ``steps`` steps (None: each object's Script Steps; 0: until
    converged), keep what succeeded and report the rest. Returns the operator's result."""
    notes = []
    with ProgressReport(context, TITLE) as report:
        sessions, failed = _set_up(planned, report)
        if pin_targets:
            try:
                apply_targets_json(sessions, pin_targets)
            except SettingsError as exc:
                for session in sessions:
                    session.cancel()
                planned.undo_added_slots()
                operator.report({'ERROR'}, str(exc))
                return {'CANCELLED'}
        counts = [steps if steps is not None else session.obj.gauss_stylization.iterations
                  for session in sessions]
        # Each object's share of the progress: its steps, or the same for all when one runs until
        # converged (how many steps that takes is not known in advance).
        shares = counts if all(counts) else [1] * len(counts)
        total, kept = max(sum(shares), 1), []
        for index, (session, count, share) in enumerate(zip(sessions, counts, shares)):
            def show(fraction, text, before=sum(shares[:index]), share=share):
                report.update((before + share * fraction) / total, text)
            try:
                taken = _advance(session, count, show)
            except SettingsError as exc:
                session.cancel()
                failed.append((session.name, str(exc)))
                continue
            except (ValueError, RuntimeError) as exc:
                session.cancel()
                failed.append((session.name, "The solver failed: %s" % exc))
                continue
            kept.append(session)
            if count == 0:
                notes.append(_until_converged_note(session, taken))
    for session in kept:
        session.keep()
    report_skipped(operator, failed, any_left=bool(kept))
    for level, text in notes:
        operator.report({level}, text)
    return {'FINISHED'} if kept else {'CANCELLED'}
